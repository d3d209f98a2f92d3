// Removal of line points the line does not need: a line between corners A and B split at p,
// with a thin patch above whose apex C sees the line under 20.2 degrees; the split cuts that
// angle in two (6.7 and 13.5 degrees). Merging the two segments gives the patch back its one
// triangle. The point must not go where the merged segment would leave the input line, where
// another line shares it, or where its faces are already good.
#include "remesh/line_point_removal.h"
#include "remesh/triangle_geometry.h"
#include "output_lattice.h"
#include "unit_square.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace mr;
using namespace mr::remesh;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kH = 0.5;  // the size: the merged segment (0.4) stays within 1.4 x it

struct SplitLine {
  OutputMesh out;
  int a, b, p, c, d;
  std::vector<LinePath> paths;
  std::vector<std::array<int, 2>> features;

  // p at a third of A-B, or `lift` off it (the input line then bends through p).
  explicit SplitLine(double lift = 0) {
    a = out.add_point(Point3(0.2, 0.4, 0), -1, PointKind::Corner);
    b = out.add_point(Point3(0.6, 0.4, 0), -1, PointKind::Corner);
    p = out.add_point(Point3(0.2 + 0.4 / 3, 0.4 + lift, 0), -1, PointKind::Line);
    c = out.add_point(Point3(0.4, 0.4 + 0.2 / std::tan(10.1 * kDeg), 0), -1, PointKind::Free);
    d = out.add_point(Point3(0.4, 0.1, 0), -1, PointKind::Free);
    out.faces = {{a, p, c}, {p, b, c}, {a, d, p}, {p, d, b}};
    out.face_patch = {0, 0, 1, 1};
    LinePath path;
    path.polyline = {out.points[a], out.points[p], out.points[b]};
    path.segment_host = {-1, -1};
    path.points = {a, p, b};
    path.arc = {0.0, (out.points[p] - out.points[a]).Norm(),
                (out.points[p] - out.points[a]).Norm() + (out.points[b] - out.points[p]).Norm()};
    path.slidable = {0, 1, 0};
    paths = {path};
    features = {{a, p}, {p, b}};
  }
};

}  // namespace

TEST(RemeshLinePointRemoval, PointSplittingTheApexAngleOfAThinPatchGoes) {
  test::UnitSquare sq(kH);
  SplitLine s;
  const double before = test::worst_angle(s.out);
  EXPECT_NEAR(before / kDeg, 6.7, 0.1);
  const std::vector<int> kept = remove_line_points(s.out, s.paths, s.features, sq.locator, sq.size, 20 * kDeg);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_TRUE(kept[0] == s.a || kept[0] == s.b);
  ASSERT_EQ(s.out.faces.size(), 2u);  // (A, B, C) above, (A, D, B) below
  EXPECT_NEAR(test::worst_angle(s.out) / kDeg, 20.2, 0.1);
  for (const auto& t : s.out.faces) {
    EXPECT_EQ(std::count(t.begin(), t.end(), s.p), 0);
    EXPECT_GT(unit_normal(s.out.points[t[0]], s.out.points[t[1]], s.out.points[t[2]])[2], 0.99);  // none turned
  }
  ASSERT_EQ(s.features.size(), 1u);  // the two segments are one
  EXPECT_EQ(std::minmax(s.features[0][0], s.features[0][1]), std::minmax(s.a, s.b));
  EXPECT_EQ(s.paths[0].points, (std::vector<int>{s.a, s.b}));
  EXPECT_EQ(s.paths[0].arc.size(), 2u);
  EXPECT_EQ(s.paths[0].slidable.size(), 2u);
  // Nothing left under the threshold: a second pass changes nothing.
  EXPECT_TRUE(remove_line_points(s.out, s.paths, s.features, sq.locator, sq.size, 20 * kDeg).empty());
}

TEST(RemeshLinePointRemoval, PointStaysWhereTheLineNeedsItOrItsFacesAreGood) {
  test::UnitSquare sq(kH);
  // The input line bends through p by 0.03 (more than 0.05 x the size from the chord A-B).
  SplitLine bent(0.03);
  const double bent_worst = test::worst_angle(bent.out);
  ASSERT_LT(bent_worst, 20 * kDeg);
  EXPECT_TRUE(remove_line_points(bent.out, bent.paths, bent.features, sq.locator, sq.size, 20 * kDeg).empty());
  EXPECT_EQ(bent.out.faces.size(), 4u);
  EXPECT_EQ(bent.features.size(), 2u);
  // Bent by 0.02, within the bound: it goes.
  SplitLine slightly(0.02);
  EXPECT_EQ(remove_line_points(slightly.out, slightly.paths, slightly.features, sq.locator, sq.size, 20 * kDeg).size(), 1u);
  // Shared with another line (not slidable): it stays.
  SplitLine shared;
  shared.paths[0].slidable[1] = 0;
  EXPECT_TRUE(remove_line_points(shared.out, shared.paths, shared.features, sq.locator, sq.size, 20 * kDeg).empty());
  EXPECT_EQ(shared.out.faces.size(), 4u);
  // Its faces above the threshold (5 degrees): it stays.
  SplitLine good;
  EXPECT_TRUE(remove_line_points(good.out, good.paths, good.features, sq.locator, sq.size, 5 * kDeg).empty());
  EXPECT_EQ(good.paths[0].points.size(), 3u);
  // A size under the merged segment's length / 1.4: it stays (the line keeps its spacing).
  test::UnitSquare fine(0.25);
  SplitLine small;
  EXPECT_TRUE(remove_line_points(small.out, small.paths, small.features, fine.locator, fine.size, 20 * kDeg).empty());
}
