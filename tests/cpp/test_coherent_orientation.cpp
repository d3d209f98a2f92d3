// One orientation per part: flipped faces of a closed cube turn back, a part keeps the
// orientation of the larger area, a Moebius band reports its conflict.
#include "common/coherent_orientation.h"
#include "shapes.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

using namespace mr;

namespace {
std::vector<std::array<int, 3>> faces_of(const TriMesh& m) {
  std::vector<std::array<int, 3>> out;
  for (const auto& f : m.face)
    out.push_back({int(vcg::tri::Index(m, f.cV(0))), int(vcg::tri::Index(m, f.cV(1))), int(vcg::tri::Index(m, f.cV(2)))});
  return out;
}
void flip(TriMesh& m, int f) { std::swap(m.face[f].V(1), m.face[f].V(2)); }
// The same triangle with the same orientation (any rotation of its corners).
bool same_oriented(const std::array<int, 3>& a, const std::array<int, 3>& b) {
  for (int r = 0; r < 3; ++r)
    if (a[0] == b[r] && a[1] == b[(r + 1) % 3] && a[2] == b[(r + 2) % 3]) return true;
  return false;
}
}  // namespace

TEST(CoherentOrientation, FlippedFacesOfACubeTurnBackAndTheMajorityWins) {
  TriMesh m;
  test::cube(m, 2);  // 48 faces of equal area
  const auto original = faces_of(m);
  for (int f : {0, 5, 17, 30, 47}) flip(m, f);
  m.face[17].SetFaceEdgeS(0);  // a selected edge follows its side
  EXPECT_GT(count_misoriented_edges(m), 0);
  const CoherentOrientation r = orient_coherently(m);
  EXPECT_EQ(r.flipped, 5);
  EXPECT_EQ(r.conflicts, 0);
  EXPECT_EQ(count_misoriented_edges(m), 0);
  const auto after = faces_of(m);
  for (size_t f = 0; f < after.size(); ++f) EXPECT_TRUE(same_oriented(after[f], original[f])) << "face " << f;
  EXPECT_TRUE(m.face[17].IsFaceEdgeS(2));
  EXPECT_FALSE(m.face[17].IsFaceEdgeS(0));
}

TEST(CoherentOrientation, AMoebiusBandKeepsOneConflict) {
  // 12 quads around a half-twisted band: P(2 pi, s) = P(0, -s).
  const int n = 12;
  std::vector<Point3> p;
  for (double w : {-0.3, 0.3})
    for (int i = 0; i < n; ++i) {
      const double t = 2 * 3.14159265358979323846 * i / n;
      p.emplace_back((1 + w * std::cos(t / 2)) * std::cos(t), (1 + w * std::cos(t / 2)) * std::sin(t), w * std::sin(t / 2));
    }
  std::vector<std::array<int, 3>> f;
  for (int i = 0; i + 1 < n; ++i) {
    f.push_back({i, n + i, n + i + 1});
    f.push_back({i, n + i + 1, i + 1});
  }
  f.push_back({n - 1, 2 * n - 1, 0});  // the last quad joins the sides crosswise
  f.push_back({n - 1, 0, n});
  TriMesh m;
  test::build(m, p, f);
  const CoherentOrientation r = orient_coherently(m);
  EXPECT_EQ(r.conflicts, 1);
  EXPECT_EQ(count_misoriented_edges(m), 1);
}
