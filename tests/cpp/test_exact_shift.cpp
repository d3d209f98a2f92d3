// The exact shift towards the origin: zero for boxes near it, exact and reversible far away.
#include "common/exact_shift.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace mr;

namespace {

/// The rounding error of a + b (Knuth's two-sum): zero exactly when the sum is exact.
double sum_error(double a, double b) {
  const double s = a + b, bb = s - a;
  return (a - (s - bb)) + (b - bb);
}

}  // namespace

TEST(ExactShift, BoxesNearTheOriginAreNotMoved) {
  EXPECT_EQ(exact_shift_towards_origin(Box3(Point3(-1, -2, -3), Point3(1, 2, 3))), Point3(0, 0, 0));
  // As far out as it is long: still near enough.
  EXPECT_EQ(exact_shift_towards_origin(Box3(Point3(1, -2, 0), Point3(2, -1, 5))), Point3(0, 0, 0));
  EXPECT_EQ(exact_shift_towards_origin(Box3()), Point3(0, 0, 0));
}

TEST(ExactShift, FarBoxesMoveToTheirNearCornerExactlyAndBack) {
  std::mt19937_64 rng(7);
  for (const double centre : {3.0, 1e6 + 0.37, -2.7e7 - 0.61, 1.5e15, -3e-200}) {
    const double size = std::fabs(centre) * 0.3;
    std::uniform_real_distribution<double> coordinate(centre - size, centre + size);
    std::vector<Point3> points(2000);
    Box3 box;
    for (auto& p : points) {
      p = Point3(coordinate(rng), coordinate(rng), coordinate(rng));
      box.Add(p);
    }
    const Point3 shift = exact_shift_towards_origin(box);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(shift[k], centre > 0 ? box.min[k] : box.max[k]) << centre;
    for (const auto& p : points)
      for (int k = 0; k < 3; ++k) {
        const double near = p[k] - shift[k];
        EXPECT_LE(std::fabs(near), 2 * size * (1 + 1e-15));
        EXPECT_EQ(sum_error(p[k], -shift[k]), 0.0);  // exact
        EXPECT_EQ(near + shift[k], p[k]);            // and back bit for bit
      }
  }
}
