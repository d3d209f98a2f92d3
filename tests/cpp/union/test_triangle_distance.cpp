// PreparedTriangle: squared distances from points, against Ericson's closest point
// (common/closest_point), on random triangles, needles and points in every Voronoi region;
// degenerate triangles against their longest side.
#include "union/triangle_distance.h"

#include "common/closest_point.h"

#include <gtest/gtest.h>

#include <random>

using namespace mr::surface_union;

namespace {

double reference_squared_distance(const V3& p, const V3& a, const V3& b, const V3& c) {
  auto P = [](const V3& x) { return mr::Point3(x[0], x[1], x[2]); };
  std::array<double, 3> bary;
  return (mr::closest_point_on_triangle(P(p), P(a), P(b), P(c), bary) - P(p)).SquaredNorm();
}

}  // namespace

TEST(UnionPreparedTriangle, MatchesTheClosestPointOnRandomTriangles) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  auto random_point = [&] { return V3{u(rng), u(rng), u(rng)}; };
  for (int trial = 0; trial < 2000; ++trial) {
    const V3 a = random_point(), b = random_point();
    V3 c = random_point();
    if (trial % 4 == 0)  // a needle: c a hair off the middle of ab
      for (int k = 0; k < 3; ++k) c[k] = (a[k] + b[k]) / 2 + 1e-4 * u(rng);
    const PreparedTriangle t(a, b, c);
    for (int s = 0; s < 10; ++s) {
      const V3 p = random_point();
      const double want = reference_squared_distance(p, a, b, c);
      EXPECT_NEAR(t.squared_distance(p), want, 1e-12 * (1 + want));
    }
  }
}

TEST(UnionPreparedTriangle, EachRegionOfARightTriangle) {
  const PreparedTriangle t({0, 0, 0}, {2, 0, 0}, {0, 2, 0});
  EXPECT_DOUBLE_EQ(t.squared_distance({0.5, 0.5, 3}), 9);    // inside: height above the plane
  EXPECT_DOUBLE_EQ(t.squared_distance({-1, -1, 0}), 2);      // corner a
  EXPECT_DOUBLE_EQ(t.squared_distance({3, -1, 0}), 2);       // corner b
  EXPECT_DOUBLE_EQ(t.squared_distance({-1, 3, 1}), 3);       // corner c
  EXPECT_DOUBLE_EQ(t.squared_distance({1, -2, 0}), 4);       // side ab
  EXPECT_DOUBLE_EQ(t.squared_distance({-3, 1, 0}), 9);       // side ac
  EXPECT_NEAR(t.squared_distance({2, 2, 0}), 2, 1e-15);      // side bc, from (1, 1)
  EXPECT_DOUBLE_EQ(t.squared_distance({1, 0, 0}), 0);        // on a side
}

TEST(UnionPreparedTriangle, DegenerateTrianglesAreTheirLongestSide) {
  // Corners in a line: the distance is to the segment between the outer two, also beside
  // its middle corner, where the nearest corner is farther.
  const PreparedTriangle line({0, 0, 0}, {1, 0, 0}, {4, 0, 0});
  EXPECT_DOUBLE_EQ(line.squared_distance({2.5, 1, 0}), 1);
  EXPECT_DOUBLE_EQ(line.squared_distance({-1, 0, 0}), 1);
  EXPECT_DOUBLE_EQ(line.squared_distance({5, 0, 2}), 5);
  // Two corners at one point (Ericson's regions divide 0 by 0 there).
  const PreparedTriangle doubled({0, 0, 0}, {0, 0, 0}, {1, 0, 0});
  EXPECT_DOUBLE_EQ(doubled.squared_distance({0.5, 1, 0}), 1);
  // All three at one point.
  const PreparedTriangle point({1, 1, 1}, {1, 1, 1}, {1, 1, 1});
  EXPECT_DOUBLE_EQ(point.squared_distance({1, 1, 3}), 4);
}
