// Valence-defect reduction on a flat patch: a regular lattice (every inner point 6-valent)
// seeded with valence defects by swaps, which the reduction must remove without lowering the
// smallest angle below min(old, floor), keeping every point on the input surface.
#include "remesh/defect_reduction.h"
#include "remesh/triangle_geometry.h"
#include "output_lattice.h"
#include "unit_square.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

using namespace mr;
using namespace mr::remesh;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;
constexpr int kN = test::kLatticeCells;

int id(int i, int j) { return test::lattice_id(i, j); }
OutputMesh lattice(const SurfaceLocator& locator) { return test::unit_lattice(locator); }

// Swaps edge a-b (two faces) to the edge between their opposite points.
void swap_edge(OutputMesh& out, int a, int b) {
  std::vector<int> pair;
  for (size_t f = 0; f < out.faces.size(); ++f) {
    const auto& t = out.faces[f];
    if (std::count(t.begin(), t.end(), a) && std::count(t.begin(), t.end(), b)) pair.push_back(int(f));
  }
  ASSERT_EQ(pair.size(), 2u);
  auto& F = out.faces[pair[0]];
  auto& G = out.faces[pair[1]];
  int z = 0;
  while (!(F[z] == a && F[(z + 1) % 3] == b) && !(F[z] == b && F[(z + 1) % 3] == a)) ++z;
  const int x = F[z], y = F[(z + 1) % 3], c = F[(z + 2) % 3];
  int d = -1;
  for (int v : G) if (v != x && v != y) d = v;
  F = {x, d, c};
  G = {d, y, c};
}

std::map<int, std::set<int>> neighbours(const OutputMesh& out) {
  std::map<int, std::set<int>> n;
  for (const auto& t : out.faces)
    for (int z = 0; z < 3; ++z) n[t[z]].insert(t[(z + 1) % 3]), n[t[(z + 1) % 3]].insert(t[z]);
  return n;
}

int irregular_inner_points(const OutputMesh& out) {
  int count = 0;
  for (const auto& [v, n] : neighbours(out))
    if (out.kind[v] == PointKind::Free && n.size() != 6) ++count;
  return count;
}

// Does one swap of an inner edge lower the squared valence deviation (6 inside, 4 on the border)?
bool one_swap_lowers_deviation(const OutputMesh& out) {
  auto n = neighbours(out);
  auto dev = [&](int v, int change) {
    if (out.kind[v] == PointKind::Corner) return 0;
    const int e = int(n[v].size()) + change - (out.kind[v] == PointKind::Free ? 6 : 4);
    return e * e;
  };
  for (const auto& [a, around] : n)
    for (int b : around) {
      std::vector<int> opposite;  // points adjacent to both a and b
      for (int c : around) if (n[b].count(c)) opposite.push_back(c);
      if (b < a || opposite.size() != 2 || n[opposite[0]].count(opposite[1])) continue;
      const int c = opposite[0], d = opposite[1];
      if (dev(a, -1) + dev(b, -1) + dev(c, 1) + dev(d, 1) < dev(a, 0) + dev(b, 0) + dev(c, 0) + dev(d, 0)) return true;
    }
  return false;
}

using test::worst_angle;

}  // namespace

TEST(RemeshDefectReduction, RemovesDefectsSeededBySwapsAndKeepsPointsOnTheSurface) {
  test::UnitSquare square(0.1);
  OutputMesh out = lattice(square.locator);
  ASSERT_EQ(irregular_inner_points(out), 0);
  // Two swaps side by side: two 5-7 pairs next to each other.
  swap_edge(out, id(3, 4), id(4, 5));
  swap_edge(out, id(6, 4), id(7, 5));
  const int seeded = irregular_inner_points(out);
  const double before = worst_angle(out);
  ASSERT_GE(seeded, 6);
  const std::unordered_set<std::uint64_t> fixed;
  const std::vector<char> all(out.points.size(), 1);
  const DefectReductionResult r = reduce_valence_defects(out, fixed, square.locator, all, all, 35 * kDeg);
  EXPECT_GT(r.swaps, 0);
  EXPECT_EQ(irregular_inner_points(out), 0);
  EXPECT_GE(worst_angle(out), std::min(before, 35 * kDeg) - 1e-12);
  EXPECT_EQ(out.faces.size(), size_t(2 * kN * kN));
  for (size_t v = 0; v < out.points.size(); ++v) {
    EXPECT_EQ(out.points[v][2], 0.0);  // on the input plane, inside the square
    EXPECT_GE(std::min(out.points[v][0], out.points[v][1]), 0.0);
    EXPECT_LE(std::max(out.points[v][0], out.points[v][1]), 1.0);
    if (out.kind[v] != PointKind::Free) {  // border points stay
      EXPECT_EQ(out.points[v], Point3(double(v % (kN + 1)) / kN, double(v / (kN + 1)) / kN, 0));
    }
  }
  // Every edge has one or two faces and no face repeats.
  std::map<std::pair<int, int>, int> edge_faces;
  for (const auto& t : out.faces)
    for (int z = 0; z < 3; ++z) edge_faces[std::minmax(t[z], t[(z + 1) % 3])]++;
  for (const auto& [e, n] : edge_faces) EXPECT_LE(n, 2);
}

TEST(RemeshDefectReduction, SwapsThatOnlyMoveADefectNeedASecondSwapToAnnihilateIt) {
  // Two neighbouring diagonals swapped: no single swap lowers the deviation (found by trying all
  // pairs of swaps on this lattice, checked below), a sequence of two removes every defect.
  test::UnitSquare square(0.1);
  OutputMesh out = lattice(square.locator);
  swap_edge(out, id(4, 4), id(5, 5));
  swap_edge(out, id(5, 4), id(6, 5));
  const int seeded = irregular_inner_points(out);
  ASSERT_EQ(seeded, 4);
  ASSERT_FALSE(one_swap_lowers_deviation(out));
  const std::unordered_set<std::uint64_t> fixed;
  const std::vector<char> all(out.points.size(), 1);
  const DefectReductionResult r = reduce_valence_defects(out, fixed, square.locator, all, all, 35 * kDeg);
  EXPECT_EQ(irregular_inner_points(out), 0);
  EXPECT_EQ(r.sequences, 1);
  EXPECT_EQ(r.swaps, 2);  // at least one kept sequence had two swaps
}
