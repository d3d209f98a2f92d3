// Wedge relaxing: lines A and B leave corner C at 20 degrees, their first points P1 and P2 one
// quarter away; one face fills the wedge between them (its angle at C is the wedge's). Merging P1
// and P2 halfway between them makes the lines share their first segment: that face goes and the
// next one between the lines sees them at about twice the angle. The merge must not happen where
// the first points are too far apart for the size, where one no longer slides, or where the
// wedge is 30 degrees or more. First points that are corners (the lines from the tip are one
// segment long, others go on from there) merge too, and take every line along. A first point
// that two lines run through (a junction) merges too, and stays where it is.
#include "remesh/wedge_relaxing.h"
#include "remesh/triangle_geometry.h"
#include "output_lattice.h"
#include "unit_square.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

using namespace mr;
using namespace mr::remesh;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kL = 0.25;  // distance of the line points from the tip

struct Wedge {
  OutputMesh out;
  int c, p1, a2, p2, b2, d, e;
  std::vector<LinePath> paths;
  std::vector<std::array<int, 2>> features;

  explicit Wedge(double angle_deg) {
    const double a = angle_deg * kDeg;
    const Point3 tip(0.2, 0.45, 0), along(std::cos(a), std::sin(a), 0), outer(std::cos(a + 1.2), std::sin(a + 1.2), 0);
    c = out.add_point(tip, 0, PointKind::Corner);
    p1 = out.add_point(tip + Point3(kL, 0, 0), 0, PointKind::Line);
    a2 = out.add_point(tip + Point3(2 * kL, 0, 0), 0, PointKind::Line);
    p2 = out.add_point(tip + along * kL, 0, PointKind::Line);
    b2 = out.add_point(tip + along * (2 * kL), 0, PointKind::Line);
    d = out.add_point(tip + Point3(kL, -kL, 0), 0, PointKind::Free);   // below line A
    e = out.add_point(tip + outer * (1.2 * kL), 0, PointKind::Free);   // beyond line B
    out.faces = {{c, p1, p2}, {p1, a2, p2}, {p2, a2, b2}, {c, d, p1}, {p1, d, a2}, {c, p2, e}, {p2, b2, e}};
    out.face_patch.assign(out.faces.size(), 0);
    paths = {path({c, p1, a2}), path({c, p2, b2})};
    features = {{c, p1}, {p1, a2}, {c, p2}, {p2, b2}};
  }

  LinePath path(const std::vector<int>& points) const {
    LinePath p;
    for (int x : points) p.polyline.push_back(out.points[x]);
    p.segment_host.assign(points.size() - 1, 0);
    p.points = points;
    for (size_t i = 0; i < points.size(); ++i) p.arc.push_back(double(i) * kL);
    p.slidable.assign(points.size(), 0);
    for (size_t i = 1; i + 1 < points.size(); ++i) p.slidable[i] = 1;
    return p;
  }

  /// P1 and P2 corners: the lines from the tip end there, two more lines go on.
  void make_first_points_corners() {
    out.kind[size_t(p1)] = out.kind[size_t(p2)] = PointKind::Corner;
    paths = {path({c, p1}), path({p1, a2}), path({c, p2}), path({p2, b2})};
  }
};

// The feature edges once P2 is P1: the tip's segment, and P1 to each line's next point.
bool features_after_merge(const Wedge& w) {
  std::vector<std::pair<int, int>> edges;
  for (const auto& f : w.features) edges.push_back(std::minmax(f[0], f[1]));
  std::sort(edges.begin(), edges.end());
  std::vector<std::pair<int, int>> expected{std::minmax(w.c, w.p1), std::minmax(w.p1, w.a2), std::minmax(w.p1, w.b2)};
  std::sort(expected.begin(), expected.end());
  return edges == expected;
}

bool all_face_up(const OutputMesh& out) {
  for (const auto& t : out.faces)
    if (!(unit_normal(out.points[t[0]], out.points[t[1]], out.points[t[2]])[2] > 0.99)) return false;
  return true;
}

}  // namespace

TEST(RemeshWedgeRelaxing, FirstPointsOfANarrowWedgeMergeHalfwayAndTheLinesShareASegment) {
  test::UnitSquare sq(0.5);
  Wedge w(20.0);
  ASSERT_TRUE(all_face_up(w.out));
  const double before = test::worst_angle(w.out);
  EXPECT_NEAR(corner_angle(w.out.points[w.c], w.out.points[w.p1], w.out.points[w.p2]) / kDeg, 20.0, 1e-9);
  const Point3 half = (w.out.points[w.p1] + w.out.points[w.p2]) * 0.5;
  const std::vector<int> merged = relax_wedge_tips(w.out, w.paths, w.features, sq.locator, sq.size);
  ASSERT_EQ(merged, std::vector<int>{w.p1});
  EXPECT_LT((w.out.points[w.p1] - half).Norm(), 1e-12);  // the flat square: halfway, on it
  ASSERT_EQ(w.out.faces.size(), 5u);                       // the wedge's face and the one beyond it went
  for (const auto& t : w.out.faces) EXPECT_EQ(std::count(t.begin(), t.end(), w.p2), 0);
  EXPECT_TRUE(all_face_up(w.out));
  // The next face between the lines, (P1, A2, B2), sees them at 2 atan(2 tan 10) = 38.9 degrees.
  const auto next = std::find(w.out.faces.begin(), w.out.faces.end(), std::array<int, 3>{w.p1, w.a2, w.b2});
  ASSERT_NE(next, w.out.faces.end());
  EXPECT_NEAR(corner_angle(w.out.points[w.p1], w.out.points[w.a2], w.out.points[w.b2]) / kDeg, 38.85, 0.01);
  EXPECT_GT(test::worst_angle(w.out), before + 5 * kDeg);
  // Both lines run through the merged point, which no longer slides; each segment is listed once.
  EXPECT_EQ(w.paths[0].points, (std::vector<int>{w.c, w.p1, w.a2}));
  EXPECT_EQ(w.paths[1].points, (std::vector<int>{w.c, w.p1, w.b2}));
  EXPECT_FALSE(w.paths[0].slidable[1] || w.paths[1].slidable[1]);
  EXPECT_TRUE(features_after_merge(w));
  // No wedge left: a second sweep changes nothing.
  EXPECT_TRUE(relax_wedge_tips(w.out, w.paths, w.features, sq.locator, sq.size).empty());
}

TEST(RemeshWedgeRelaxing, WedgesStayWhereTheyAreWideOrThePointsFarApartOrShared) {
  // 30 degrees or more is no wedge tip.
  test::UnitSquare sq(0.5);
  Wedge wide(32.0);
  EXPECT_TRUE(relax_wedge_tips(wide.out, wide.paths, wide.features, sq.locator, sq.size).empty());
  EXPECT_EQ(wide.out.faces.size(), 7u);
  // First points 0.087 apart against 0.6 x a size of 0.1: the lines would leave the input by more
  // than the elements can show.
  test::UnitSquare fine(0.1);
  Wedge far(20.0);
  EXPECT_TRUE(relax_wedge_tips(far.out, far.paths, far.features, fine.locator, fine.size).empty());
  EXPECT_EQ(far.features.size(), 4u);
  // P2 shared with a third line: it stays.
  Wedge shared(20.0);
  shared.paths[1].slidable[1] = 0;
  EXPECT_TRUE(relax_wedge_tips(shared.out, shared.paths, shared.features, sq.locator, sq.size).empty());
  EXPECT_EQ(shared.out.faces.size(), 7u);
}

TEST(RemeshWedgeRelaxing, CornersBesideANarrowWedgeMergeAndEveryLineThroughThemFollows) {
  test::UnitSquare sq(0.5);
  Wedge w(20.0);
  w.make_first_points_corners();
  const double before = test::worst_angle(w.out);
  ASSERT_EQ(relax_wedge_tips(w.out, w.paths, w.features, sq.locator, sq.size), std::vector<int>{w.p1});
  EXPECT_EQ(w.out.faces.size(), 5u);
  EXPECT_TRUE(all_face_up(w.out));
  EXPECT_GT(test::worst_angle(w.out), before + 5 * kDeg);
  EXPECT_EQ(w.out.kind[size_t(w.p1)], PointKind::Corner);
  ASSERT_EQ(w.paths.size(), 4u);
  EXPECT_EQ(w.paths[0].points, (std::vector<int>{w.c, w.p1}));
  EXPECT_EQ(w.paths[1].points, (std::vector<int>{w.p1, w.a2}));
  EXPECT_EQ(w.paths[2].points, (std::vector<int>{w.c, w.p1}));  // the tip's two lines are one now
  EXPECT_EQ(w.paths[3].points, (std::vector<int>{w.p1, w.b2}));
  EXPECT_TRUE(features_after_merge(w));
}

TEST(RemeshWedgeRelaxing, AJunctionBesideANarrowWedgeTakesTheOtherPointAndStaysWhereItIs) {
  // A third line runs from corner D through P1 to the tip, on line A's first segment (lines that
  // share a stretch, as where tiny lines merged at a sphere cluster's triple points).
  test::UnitSquare sq(0.5);
  Wedge w(20.0);
  w.out.kind[size_t(w.d)] = PointKind::Corner;
  w.paths.push_back(w.path({w.d, w.p1, w.c}));
  w.features.push_back({w.d, w.p1});
  const Point3 junction = w.out.points[w.p1];
  const double before = test::worst_angle(w.out);
  ASSERT_EQ(relax_wedge_tips(w.out, w.paths, w.features, sq.locator, sq.size), std::vector<int>{w.p1});
  EXPECT_EQ(w.out.points[w.p1], junction);  // moved, it would move line D too
  EXPECT_EQ(w.out.faces.size(), 5u);
  EXPECT_TRUE(all_face_up(w.out));
  EXPECT_GT(test::worst_angle(w.out), before + 5 * kDeg);
  EXPECT_EQ(w.paths[0].points, (std::vector<int>{w.c, w.p1, w.a2}));
  EXPECT_EQ(w.paths[1].points, (std::vector<int>{w.c, w.p1, w.b2}));
  EXPECT_EQ(w.paths[2].points, (std::vector<int>{w.d, w.p1, w.c}));
  for (const auto& path : w.paths) EXPECT_FALSE(path.slidable[1]);
  // Where both first points are junctions neither can give way: nothing merges.
  // (A third line from corner D below line A through P1, a fourth from corner E beyond line B
  // through P2, each along face edges.)
  Wedge both(20.0);
  for (const auto& [from, p] : {std::pair{both.d, both.p1}, std::pair{both.e, both.p2}}) {
    both.out.kind[size_t(from)] = PointKind::Corner;
    both.paths.push_back(both.path({from, p, both.c}));
    both.features.push_back({from, p});
  }
  EXPECT_TRUE(relax_wedge_tips(both.out, both.paths, both.features, sq.locator, sq.size).empty());
  EXPECT_EQ(both.out.faces.size(), 7u);
}
