// Points whose faces make more than one fan are counted; fans open or closed are not. Patches
// that put an edge of their own on another patch's line segment are found.
#include "remesh/mesh_measures.h"
#include "remesh/patch_retry.h"

#include <gtest/gtest.h>

using namespace mr;
using namespace mr::remesh;

namespace {

OutputMesh points(std::initializer_list<Point3> ps) {
  OutputMesh out;
  for (const Point3& p : ps) out.add_point(p, 0, PointKind::Free);
  return out;
}

}  // namespace

TEST(PinchedPoints, TwoFansAtOnePointMakeItPinched) {
  // A bow tie: two triangles that share only point 0.
  OutputMesh out = points({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}});
  out.faces = {{0, 1, 2}, {0, 3, 4}};
  out.face_patch = {0, 0};
  EXPECT_EQ(count_pinched_points(out), 1);
  // Joined by a third face across the gap, the faces at 0 make one (open) fan.
  out.faces.push_back({0, 2, 3});
  out.face_patch.push_back(0);
  EXPECT_EQ(count_pinched_points(out), 0);
}

TEST(PinchedPoints, ClosedFansAndBordersAreManifold) {
  // A square fan around its centre (closed), and its rim points (open fans).
  OutputMesh out = points({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}});
  out.faces = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}};
  out.face_patch = {0, 0, 0, 0};
  EXPECT_EQ(count_pinched_points(out), 0);
  // A second square fan touching the first at its rim point 1: that point is pinched.
  for (const Point3& p : {Point3(2, 0, 0), Point3(1, 1, 1), Point3(1, -1, 1)}) out.add_point(p, 0, PointKind::Free);
  out.faces.push_back({1, 5, 6});
  out.faces.push_back({1, 7, 5});
  out.face_patch.insert(out.face_patch.end(), {1, 1});
  EXPECT_EQ(count_pinched_points(out), 1);
}

TEST(PinchedPoints, PatchesThatTookALineSegmentOfOtherPatchesAreFound) {
  // Corners a and b joined by a one-segment line between patches 1 and 2; patch 0, meshed
  // first, had both on its border and put an edge of its own there: four faces on a-b.
  OutputMesh out;
  const int a = out.add_point(Point3(0, 0, 0), 0, PointKind::Corner);
  const int b = out.add_point(Point3(1, 0, 0), 0, PointKind::Corner);
  const int p = out.add_point(Point3(0.5, 1, 0), 0, PointKind::Free);
  const int q = out.add_point(Point3(0.5, -1, 0), 0, PointKind::Free);
  const int r = out.add_point(Point3(0.5, 0, 1), 0, PointKind::Free);
  const int s = out.add_point(Point3(0.5, 0, -1), 0, PointKind::Free);
  out.faces = {{a, b, p}, {b, a, q}, {b, a, r}, {a, b, s}};
  out.face_patch = {0, 0, 1, 2};
  const std::vector<std::array<int, 2>> line{{a, b}};
  EXPECT_EQ(patches_on_taken_lines(out, line), std::vector<int>{0});
  // Not a line segment: nothing to find (the pinched-point checks see such edges).
  EXPECT_TRUE(patches_on_taken_lines(out, {}).empty());
  // Two faces only, both of one patch (a line dangling inside it): nothing taken.
  out.faces.resize(2);
  out.face_patch.resize(2);
  EXPECT_TRUE(patches_on_taken_lines(out, line).empty());
}
