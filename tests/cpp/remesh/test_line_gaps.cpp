// Lines that pass close without meeting (close_line_gaps): line A runs straight along y = 0.4,
// line B comes down from 0.15 above it to 0.02 above it at x = 0.35 and goes back up (a neck,
// as where two intersection circles of a sphere cluster nearly touch). The faces between the
// lines at the neck have 4.6 degrees. With a point of each line at the neck, the two merge;
// with B's point facing the middle of one long segment of A (a cap), B's point joins line A.
// Either way the lines meet at the neck and no face there stays under 30 degrees. Nothing
// changes where the lines are farther apart than the size allows, or where no face is under
// the bound.
#include "remesh/wedge_relaxing.h"
#include "remesh/triangle_geometry.h"
#include "output_lattice.h"
#include "unit_square.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>

using namespace mr;
using namespace mr::remesh;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr double kGap = 0.02;  // B's lowest point above line A

LinePath path_of(const OutputMesh& out, const std::vector<int>& points) {
  LinePath p;
  for (int x : points) p.polyline.push_back(out.points[x]);
  p.segment_host.assign(points.size() - 1, 0);
  p.points = points;
  for (size_t i = 0; i < points.size(); ++i) p.arc.push_back(0.25 * double(i));
  p.slidable.assign(points.size(), 0);
  for (size_t i = 1; i + 1 < points.size(); ++i) p.slidable[i] = 1;
  return p;
}

struct Neck {
  OutputMesh out;
  int a0, a1, a2, b0, b1, b2, d, e;  // a1 = -1 in the cap: A is one segment a0-a2
  std::vector<LinePath> paths;
  std::vector<std::array<int, 2>> features;

  /// `a_point_at_neck`: A has a point under B's (two points merge), else one segment (a cap).
  explicit Neck(bool a_point_at_neck) {
    a0 = out.add_point({0.1, 0.4, 0}, 0, PointKind::Corner);
    a1 = a_point_at_neck ? out.add_point({0.35, 0.4, 0}, 0, PointKind::Line) : -1;
    a2 = out.add_point({0.6, 0.4, 0}, 0, PointKind::Corner);
    b0 = out.add_point({0.1, 0.55, 0}, 0, PointKind::Corner);
    b1 = out.add_point({0.35, 0.4 + kGap, 0}, 0, PointKind::Line);
    b2 = out.add_point({0.6, 0.55, 0}, 0, PointKind::Corner);
    d = out.add_point({0.35, 0.15, 0}, 0, PointKind::Free);  // below A
    e = out.add_point({0.35, 0.7, 0}, 0, PointKind::Free);   // above B
    if (a_point_at_neck)
      out.faces = {{a0, a1, b1}, {a0, b1, b0}, {a1, a2, b1}, {b1, a2, b2}, {a0, d, a1}, {a1, d, a2}, {b0, b1, e}, {b1, b2, e}};
    else
      out.faces = {{a0, a2, b1}, {a0, b1, b0}, {b1, a2, b2}, {a2, a0, d}, {b0, b1, e}, {b1, b2, e}};
    out.face_patch.assign(out.faces.size(), 0);
    paths = {path_of(out, a_point_at_neck ? std::vector<int>{a0, a1, a2} : std::vector<int>{a0, a2}),
             path_of(out, {b0, b1, b2})};
    for (const auto& p : paths)
      for (size_t i = 0; i + 1 < p.points.size(); ++i) features.push_back({p.points[i], p.points[i + 1]});
  }
};

bool all_face_up(const OutputMesh& out) {
  for (const auto& t : out.faces)
    if (!(unit_normal(out.points[t[0]], out.points[t[1]], out.points[t[2]])[2] > 0.99)) return false;
  return true;
}

/// The neck as built: every face up, the worst 4.57 degrees (atan(0.02 / 0.25)) between the lines.
void expect_neck_as_built(const Neck& n) {
  ASSERT_TRUE(all_face_up(n.out));
  EXPECT_NEAR(test::worst_angle(n.out) / kDeg, 4.57, 0.01);
}

std::vector<std::pair<int, int>> sorted_edges(std::vector<std::array<int, 2>> edges) {
  std::vector<std::pair<int, int>> out;
  for (const auto& e : edges) out.push_back(std::minmax(e[0], e[1]));
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST(RemeshLineGaps, PointsOfTwoLinesAtANeckMergeAndTheLinesMeetThere) {
  test::UnitSquare sq(0.5);
  Neck n(true);
  expect_neck_as_built(n);
  const std::vector<int> merged = close_line_gaps(n.out, n.paths, n.features, sq.locator, sq.size, 30 * kDeg);
  ASSERT_EQ(merged.size(), 1u);
  const int m = merged[0];
  ASSERT_TRUE(m == n.a1 || m == n.b1);
  const int gone = m == n.a1 ? n.b1 : n.a1;
  EXPECT_NEAR(n.out.points[m][1], 0.4 + kGap / 2, 1e-12);  // halfway, on the flat square
  EXPECT_EQ(n.out.faces.size(), 6u);                         // the two faces on the merged edge went
  for (const auto& t : n.out.faces) EXPECT_EQ(std::count(t.begin(), t.end(), gone), 0);
  EXPECT_TRUE(all_face_up(n.out));
  EXPECT_GT(test::worst_angle(n.out) / kDeg, 30.0);
  EXPECT_EQ(n.paths[0].points, (std::vector<int>{n.a0, m, n.a2}));
  EXPECT_EQ(n.paths[1].points, (std::vector<int>{n.b0, m, n.b2}));
  EXPECT_FALSE(n.paths[0].slidable[1] || n.paths[1].slidable[1]);
  EXPECT_EQ(sorted_edges(n.features),
            sorted_edges({{n.a0, m}, {m, n.a2}, {n.b0, m}, {m, n.b2}}));
  EXPECT_TRUE(close_line_gaps(n.out, n.paths, n.features, sq.locator, sq.size, 30 * kDeg).empty());
}

TEST(RemeshLineGaps, APointFacingTheMiddleOfAnotherLinesSegmentJoinsThatLine) {
  test::UnitSquare sq(0.5);
  Neck n(false);
  expect_neck_as_built(n);
  const std::vector<int> snapped = close_line_gaps(n.out, n.paths, n.features, sq.locator, sq.size, 30 * kDeg);
  ASSERT_EQ(snapped, std::vector<int>{n.b1});
  EXPECT_NEAR(n.out.points[n.b1][1], 0.4 + kGap / 2, 1e-12);  // halfway to the segment
  EXPECT_EQ(n.out.faces.size(), 6u);                           // the cap's side flipped: as many faces
  EXPECT_TRUE(all_face_up(n.out));
  EXPECT_GT(test::worst_angle(n.out) / kDeg, 30.0);
  // The segment's faces now meet at B's point: the edge from it to the point below A is there.
  const bool flipped = std::any_of(n.out.faces.begin(), n.out.faces.end(), [&](const std::array<int, 3>& t) {
    return std::count(t.begin(), t.end(), n.b1) && std::count(t.begin(), t.end(), n.d);
  });
  EXPECT_TRUE(flipped);
  EXPECT_EQ(n.paths[0].points, (std::vector<int>{n.a0, n.b1, n.a2}));
  EXPECT_EQ(n.paths[0].arc, (std::vector<double>{0.0, 0.125, 0.25}));
  EXPECT_EQ(n.paths[1].points, (std::vector<int>{n.b0, n.b1, n.b2}));
  EXPECT_FALSE(n.paths[0].slidable[1] || n.paths[1].slidable[1]);
  EXPECT_EQ(sorted_edges(n.features),
            sorted_edges({{n.a0, n.b1}, {n.b1, n.a2}, {n.b0, n.b1}, {n.b1, n.b2}}));
  EXPECT_TRUE(close_line_gaps(n.out, n.paths, n.features, sq.locator, sq.size, 30 * kDeg).empty());
}

TEST(RemeshLineGaps, LinesStayApartWhereTheGapIsWideForTheSizeOrNoFaceIsUnderTheBound) {
  // A size of 0.05: the neck's 0.02 is 0.4 x the size, wider than the elements leave alone.
  test::UnitSquare fine(0.05);
  for (bool merge : {true, false}) {
    Neck n(merge);
    EXPECT_TRUE(close_line_gaps(n.out, n.paths, n.features, fine.locator, fine.size, 30 * kDeg).empty());
    EXPECT_EQ(n.features.size(), merge ? 4u : 3u);
  }
  // Faces of 4.6 degrees are not under a bound of 3.
  test::UnitSquare sq(0.5);
  for (bool merge : {true, false}) {
    Neck n(merge);
    const size_t faces = n.out.faces.size();
    EXPECT_TRUE(close_line_gaps(n.out, n.paths, n.features, sq.locator, sq.size, 3 * kDeg).empty());
    EXPECT_EQ(n.out.faces.size(), faces);
  }
  // B's point shared with a third line (it no longer slides): it stays.
  Neck shared(true);
  shared.paths[1].slidable[1] = 0;
  shared.paths[0].slidable[1] = 0;
  EXPECT_TRUE(close_line_gaps(shared.out, shared.paths, shared.features, sq.locator, sq.size, 30 * kDeg).empty());
}
