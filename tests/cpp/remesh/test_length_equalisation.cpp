// Edge-length moves of the post-pass on a flat patch: a lattice of the size h with one point
// pushed or added so that an edge is short; the moves must bring every edge back to
// [0.7, 1.4] x h, keep the points on the input and never lower the worst angle below
// min(old, floor); line and corner points never go.
#include "remesh/length_equalisation.h"
#include "remesh/triangle_geometry.h"
#include "output_lattice.h"
#include "unit_square.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

using namespace mr;
using namespace mr::remesh;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr int kN = test::kLatticeCells;  // edges of 0.1, diagonals of 0.141
constexpr double kH = 0.11;  // so that all of them are in range

int id(int i, int j) { return test::lattice_id(i, j); }
OutputMesh lattice(const SurfaceLocator& locator) { return test::unit_lattice(locator); }

int edges_out_of_range(const OutputMesh& out) {
  std::set<std::pair<int, int>> edges;
  for (const auto& t : out.faces)
    for (int z = 0; z < 3; ++z) edges.insert(std::minmax(t[z], t[(z + 1) % 3]));
  int n = 0;
  for (const auto& [a, b] : edges) {
    const double l = (out.points[a] - out.points[b]).Norm() / kH;
    n += l < kShortEdge || l > kLongEdge;
  }
  return n;
}

using test::worst_angle;

}  // namespace

TEST(RemeshLengthEqualisation, PointPushedTowardsANeighbourMovesBackWithinTheSurface) {
  test::UnitSquare sq(kH);
  OutputMesh out = lattice(sq.locator);
  const int v = id(5, 5);
  out.points[v] = Point3(0.5 + 0.06, 0.5 + 0.01, 0);  // 0.37 h from (6, 5), 1.46 h from (4, 5)
  out.host[v] = sq.locator.locate(out.points[v], -1, Point3(0, 0, 1), -1, 0.2).face;
  ASSERT_EQ(edges_out_of_range(lattice(sq.locator)), 0);
  ASSERT_GE(edges_out_of_range(out), 2);
  const double before = worst_angle(out);
  const std::vector<char> movable(out.points.size(), 1);

  int moves = 0;
  for (int sweep = 0; sweep < 3; ++sweep) moves += relax_edge_lengths(out, sq.locator, sq.size, movable, 30 * kDeg);
  EXPECT_GE(moves, 1);
  EXPECT_EQ(edges_out_of_range(out), 0);
  EXPECT_GE(worst_angle(out), std::min(before, 30 * kDeg) - 1e-12);
  for (const auto& p : out.points) EXPECT_NEAR(p[2], 0.0, 1e-12);
  // The moves stay local: only the pushed point and its neighbours had edges out of range.
  const OutputMesh untouched = lattice(sq.locator);
  for (size_t u = 0; u < out.points.size(); ++u) {
    if ((untouched.points[u] - untouched.points[v]).Norm() > 2 * kH) {
      EXPECT_EQ(out.points[u], untouched.points[u]);
    }
  }
}

TEST(RemeshLengthEqualisation, FreePointNextToAnotherCollapsesOntoIt) {
  test::UnitSquare sq(kH);
  OutputMesh out = lattice(sq.locator);
  // A free point added inside face (a, b, c) of the lattice, 0.3 h from its corner a.
  const std::array<int, 3> abc = out.faces[2 * (4 * kN + 4)];  // cell (4, 4), lower face
  const int a = abc[0];
  const Point3 at = out.points[a] + (out.points[abc[1]] + out.points[abc[2]] - out.points[a] * 2).Normalize() * (0.3 * kH);
  const int p = out.add_point(at, sq.locator.locate(at, -1, Point3(0, 0, 1), -1, 0.2).face, PointKind::Free);
  out.faces[2 * (4 * kN + 4)] = {abc[0], abc[1], p};
  out.faces.push_back({abc[1], abc[2], p});
  out.faces.push_back({abc[2], abc[0], p});
  out.face_patch.assign(out.faces.size(), 0);
  ASSERT_GE(edges_out_of_range(out), 1);
  const double before = worst_angle(out);

  const std::vector<char> movable(out.points.size(), 1);
  EXPECT_EQ(collapse_short_edges(out, {}, sq.locator, sq.size, movable, 30 * kDeg), 1);
  EXPECT_EQ(out.faces.size(), size_t(2 * kN * kN));
  for (const auto& t : out.faces) EXPECT_EQ(std::count(t.begin(), t.end(), p), 0);
  EXPECT_EQ(edges_out_of_range(out), 0);
  EXPECT_GE(worst_angle(out), std::min(before, 30 * kDeg));
  // The lattice is whole again: every face keeps its counter-clockwise turn (no fold).
  for (const auto& t : out.faces) {
    const Point3 n = (out.points[t[1]] - out.points[t[0]]) ^ (out.points[t[2]] - out.points[t[0]]);
    EXPECT_GT(n[2], 0);
  }
}

TEST(RemeshLengthEqualisation, LinePointsAndFeatureEdgesStay) {
  test::UnitSquare sq(kH);
  OutputMesh out = lattice(sq.locator);
  // Two line points of the bottom side 0.2 h apart: a short edge no move may fix.
  out.points[id(5, 0)] = Point3(0.58, 0, 0);
  out.host[id(5, 0)] = sq.locator.locate(out.points[id(5, 0)], -1, Point3(0, 0, 1), -1, 0.2).face;
  const OutputMesh before = out;
  std::unordered_set<std::uint64_t> fixed;
  for (int i = 0; i < kN; ++i) fixed.insert(OutputMesh::edge_key(id(i, 0), id(i + 1, 0)));
  std::vector<char> movable(out.points.size(), 1);
  EXPECT_EQ(collapse_short_edges(out, fixed, sq.locator, sq.size, movable, 30 * kDeg), 0);
  EXPECT_EQ(out.faces, before.faces);
  relax_edge_lengths(out, sq.locator, sq.size, movable, 30 * kDeg);
  for (int i = 0; i <= kN; ++i) EXPECT_EQ(out.points[id(i, 0)], before.points[id(i, 0)]);
}

TEST(RemeshLengthEqualisation, LongEdgeIsSplitAtItsMiddleOnTheSurface) {
  test::UnitSquare sq(kH);
  // Two faces on the long edge a-b (2.7 h) whose apexes c and d lie 0.9 h from its middle.
  OutputMesh out;
  for (const Point3& p : {Point3(0.3, 0.5, 0), Point3(0.6, 0.5, 0), Point3(0.45, 0.6, 0), Point3(0.45, 0.4, 0)})
    out.add_point(p, sq.locator.locate(p, -1, Point3(0, 0, 1), -1, 0.2).face, PointKind::Line);
  out.faces = {{0, 1, 2}, {1, 0, 3}};
  out.face_patch = {0, 0};
  const double before = worst_angle(out);

  std::vector<char> movable(out.points.size(), 1);
  EXPECT_EQ(split_long_edges(out, {}, sq.locator, sq.size, movable, 30 * kDeg), 1);
  ASSERT_EQ(out.points.size(), 5u);
  EXPECT_EQ(movable.size(), 5u);
  EXPECT_EQ(out.kind[4], PointKind::Free);
  EXPECT_EQ(out.faces.size(), 4u);
  EXPECT_NEAR((out.points[4] - Point3(0.45, 0.5, 0)).Norm(), 0.0, 1e-12);
  for (const auto& t : out.faces) {
    EXPECT_EQ(std::count(t.begin(), t.end(), 4), 1);
    const Point3 n = (out.points[t[1]] - out.points[t[0]]) ^ (out.points[t[2]] - out.points[t[0]]);
    EXPECT_GT(n[2], 0);
  }
  EXPECT_GE(worst_angle(out), std::min(before, 30 * kDeg));
  // A fixed (feature) edge stays whole.
  OutputMesh kept;
  for (int v = 0; v < 4; ++v) kept.add_point(out.points[v], out.host[v], PointKind::Line);
  kept.faces = {{0, 1, 2}, {1, 0, 3}};
  kept.face_patch = {0, 0};
  std::vector<char> all(4, 1);
  EXPECT_EQ(split_long_edges(kept, {OutputMesh::edge_key(0, 1)}, sq.locator, sq.size, all, 30 * kDeg), 0);
  EXPECT_EQ(kept.faces.size(), 2u);
}
