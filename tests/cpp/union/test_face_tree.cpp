// FaceTree: distances from points to a fixed triangle surface, against a scan of every face.
#include "union/face_tree.h"

#include "common/closest_point.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>
#include <vector>

using namespace mr::surface_union;

namespace {

double scanned_distance(const V3& p, const std::vector<V3>& v, const std::vector<std::array<int, 3>>& f) {
  double best = 1e300;
  std::array<double, 3> bary;
  const mr::Point3 q(p[0], p[1], p[2]);
  for (const auto& t : f) {
    auto P = [&](int i) { return mr::Point3(v[i][0], v[i][1], v[i][2]); };
    best = std::min(best, (mr::closest_point_on_triangle(q, P(t[0]), P(t[1]), P(t[2]), bary) - q).Norm());
  }
  return best;
}

// A wavy height field over [0,1]^2 with long thin triangles in every other row (CAD needles).
void wavy_sheet(std::vector<V3>& v, std::vector<std::array<int, 3>>& f) {
  const int n = 30;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = double(i) / n, y = j % 2 ? (j - 0.98) / n : double(j) / n;
      v.push_back({x, y, 0.05 * std::sin(6 * x) * std::cos(5 * y)});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      f.push_back({a, b, d});
      f.push_back({a, d, c});
    }
}

}  // namespace

TEST(UnionFaceTree, DistanceEqualsTheScanOfAllFaces) {
  std::vector<V3> v;
  std::vector<std::array<int, 3>> f;
  wavy_sheet(v, f);
  std::vector<int> all(f.size());
  std::iota(all.begin(), all.end(), 0);
  const FaceTree tree(v, f, all);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.2, 1.2), h(-0.3, 0.3);
  std::uniform_int_distribution<int> face(0, int(f.size()) - 1);
  // Faces tried first change the work, not the answer: any faces, far or near.
  FaceTree::Recent recent;
  recent.faces = {face(rng), face(rng), -1, face(rng)};
  for (int k = 0; k < 500; ++k) {
    const V3 p{u(rng), u(rng), h(rng)};
    const double exact = scanned_distance(p, v, f);
    // No shortcut: the nearest face.
    EXPECT_NEAR(tree.distance(p, 0, 10), exact, 1e-12);
    EXPECT_NEAR(tree.distance(p, 0, 10, &recent), exact, 1e-12);
    // Faces beyond the limit are not looked at: the result then says "beyond".
    const double limit = 0.5 * exact;
    EXPECT_GT(tree.distance(p, 0, limit), limit);
    // Enough: some face within it ends the search; beyond it the distance is exact.
    const double enough = 2 * exact + 1e-9;
    const double d = tree.distance(p, enough, 10);
    EXPECT_LE(d, enough);
    EXPECT_GE(d, exact - 1e-12);
    const double fixed = 0.02, e = tree.distance(p, fixed, 10, &recent);
    if (exact > fixed) EXPECT_NEAR(e, exact, 1e-12);
    else EXPECT_LE(e, fixed);
    EXPECT_GE(e, exact - 1e-12);
  }
}

TEST(UnionFaceTree, OnlyTheChosenFacesCount) {
  std::vector<V3> v;
  std::vector<std::array<int, 3>> f;
  wavy_sheet(v, f);
  // Only the faces with x < 0.5: a point above x = 0.9 is far from all of them.
  std::vector<int> left;
  for (int i = 0; i < int(f.size()); ++i)
    if (v[f[i][0]][0] < 0.5 && v[f[i][1]][0] < 0.5 && v[f[i][2]][0] < 0.5) left.push_back(i);
  const FaceTree tree(v, f, left);
  std::vector<std::array<int, 3>> chosen;
  for (int i : left) chosen.push_back(f[i]);
  for (const V3& p : {V3{0.9, 0.5, 0}, V3{0.2, 0.5, 0.3}})
    EXPECT_NEAR(tree.distance(p, 0, 10), scanned_distance(p, v, chosen), 1e-12);
  EXPECT_GT(tree.distance({0.9, 0.5, 0}, 0, 10), 0.39);
  EXPECT_TRUE(FaceTree().empty());
  EXPECT_GT(FaceTree().distance({0, 0, 0}, 0, 1), 1);
}
