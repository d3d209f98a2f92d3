// Local repair: a hole opened around trouble spots is bounded by a consistent front, and the
// front meshes it again so the patch is whole.
#include "remesh/advancing_front.h"
#include "remesh/local_repair.h"
#include "unit_square.h"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <utility>

using namespace mr;
using namespace mr::remesh;

namespace {

// The unit square meshed by the front from its boundary; returns that front.
std::vector<FrontSide> mesh_square(OutputMesh& out, const test::UnitSquare& sq) {
  const std::vector<FrontSide> front = test::UnitSquare::boundary(out);
  advance_front(out, front, 0, sq.locator, sq.size);
  return front;
}

double area(const OutputMesh& out) {
  double a = 0;
  for (const auto& f : out.faces) a += 0.5 * ((out.points[f[1]] - out.points[f[0]]) ^ (out.points[f[2]] - out.points[f[0]]))[2];
  return a;
}

int nearest_point(const OutputMesh& out, const Point3& p) {
  int best = 0;
  for (size_t v = 1; v < out.points.size(); ++v)
    if ((out.points[v] - p).Norm() < (out.points[best] - p).Norm()) best = int(v);
  return best;
}

}  // namespace

TEST(RemeshLocalRepair, HoleAroundASpotHasAClosedFrontAndIsMeshedAgain) {
  const test::UnitSquare sq(0.1);
  OutputMesh out;
  const std::vector<FrontSide> initial = mesh_square(out, sq);
  const size_t faces_before = out.faces.size();
  ASSERT_NEAR(area(out), 1.0, 1e-9);

  const int spot = nearest_point(out, Point3(0.5, 0.5, 0));
  const std::vector<FrontSide> hole = open_hole_around(out, 0, initial, {}, {spot}, 0.2);
  ASSERT_FALSE(hole.empty());
  EXPECT_LT(out.faces.size(), faces_before);
  const double removed = 1.0 - area(out);
  EXPECT_GT(removed, 3.14159 * 0.2 * 0.2 * 0.9);  // at least the disc of the radius (less a margin)
  // Every point of the hole's front has one side in and one out, and every side has a kept face
  // on its right (the unmeshed hole on its left).
  std::map<int, int> balance;
  std::set<std::pair<int, int>> kept;
  for (const auto& f : out.faces)
    for (int z = 0; z < 3; ++z) kept.insert({f[z], f[(z + 1) % 3]});
  for (const auto& sd : hole) {
    balance[sd[0]]++;
    balance[sd[1]]--;
    EXPECT_TRUE(kept.count({sd[1], sd[0]}));
    EXPECT_FALSE(kept.count({sd[0], sd[1]}));
  }
  for (const auto& [v, b] : balance) EXPECT_EQ(b, 0);

  const FrontResult r = advance_front(out, hole, 0, sq.locator, sq.size.scaled(0.8));
  EXPECT_EQ(r.unmeshed_sides, 0);
  EXPECT_NEAR(area(out), 1.0, 1e-9);
  EXPECT_EQ(bad_edges(out), 0);
}

TEST(RemeshLocalRepair, NoSpotRemovesNothingAndOversizedFacesAreFound) {
  const test::UnitSquare sq(0.1);
  OutputMesh out;
  const std::vector<FrontSide> initial = mesh_square(out, sq);
  const size_t faces = out.faces.size();
  EXPECT_TRUE(open_hole_around(out, 0, initial, {}, {}, 0.2).empty());
  EXPECT_EQ(out.faces.size(), faces);
  // Elements of size 0.1: none has a side over 0.2, and a face across the square has.
  EXPECT_TRUE(oversized_face_points(out, 0, 0.2).empty());
  const int a = nearest_point(out, Point3(0, 0, 0)), b = nearest_point(out, Point3(1, 0, 0)), c = nearest_point(out, Point3(1, 1, 0));
  out.faces.push_back({a, b, c});
  out.face_patch.push_back(0);
  const std::vector<int> spots = oversized_face_points(out, 0, 0.2);
  EXPECT_EQ(spots, (std::vector<int>{std::min({a, b, c}), a + b + c - std::min({a, b, c}) - std::max({a, b, c}), std::max({a, b, c})}));
  EXPECT_TRUE(oversized_face_points(out, 1, 0.2).empty());  // another patch
}

TEST(RemeshLocalRepair, StrayFacesAreThoseOffTheInput) {
  const test::UnitSquare sq(0.1);
  OutputMesh out;
  mesh_square(out, sq);
  // Every point lies on the square: no face strays.
  EXPECT_TRUE(stray_face_points(out, 0, sq.locator, 0.05).empty());
  // Lift one free point 0.3 off the plane: the centroids of its faces are 0.1 off, and only the
  // points of those faces are returned.
  const int v = nearest_point(out, Point3(0.5, 0.5, 0));
  ASSERT_EQ(out.kind[v], PointKind::Free);
  out.points[v][2] = 0.3;
  const std::vector<int> stray = stray_face_points(out, 0, sq.locator, 0.05);
  EXPECT_TRUE(std::binary_search(stray.begin(), stray.end(), v));
  int ring = 0;
  for (const auto& f : out.faces) ring += std::count(f.begin(), f.end(), v);
  EXPECT_EQ(int(stray.size()), ring + 1);  // v and its ring of neighbours (a closed fan)
  EXPECT_TRUE(stray_face_points(out, 0, sq.locator, 0.2).empty());
}
