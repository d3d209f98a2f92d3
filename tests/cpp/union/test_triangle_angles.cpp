// angle_of against std::atan2 (within a few ulps of pi) over the whole half plane y >= 0,
// at the reduction's seams and its edge cases; smallest_angle of known triangles.
#include "union/triangle_angles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace mr::surface_union;

TEST(UnionAngles, AngleOfMatchesTheLibrarysAtan2) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_real_distribution<double> e(-30, 30);
  const double ulps = 4 * std::numeric_limits<double>::epsilon() * M_PI;
  for (int trial = 0; trial < 200000; ++trial) {
    const double scale = std::pow(10.0, e(rng));
    const double y = std::fabs(u(rng)) * scale, x = u(rng) * scale;
    ASSERT_NEAR(angle_of(y, x), std::atan2(y, x), ulps) << y << " " << x;
  }
  // At the seams of the reduction (tan((k + 1/2) pi / 16)), at 0, 45, 90, 180 degrees.
  for (int k = 0; k < 4; ++k) {
    const double t = std::tan((k + 0.5) * M_PI / 16);
    for (double d : {-1e-15, 0.0, 1e-15}) ASSERT_NEAR(angle_of(t + d, 1), std::atan2(t + d, 1), ulps);
  }
  EXPECT_EQ(angle_of(0, 1), 0.0);
  EXPECT_NEAR(angle_of(1, 1), M_PI / 4, ulps);
  EXPECT_NEAR(angle_of(1, 0), M_PI / 2, ulps);
  EXPECT_NEAR(angle_of(0, -1), M_PI, ulps);
  EXPECT_EQ(angle_of(0, 0), 0.0);
  EXPECT_TRUE(std::isnan(angle_of(std::nan(""), 1)));
  EXPECT_NEAR(angle_of(INFINITY, 1), M_PI / 2, ulps);
}

TEST(UnionAngles, SmallestAngleOfKnownTriangles) {
  const double deg = M_PI / 180;
  EXPECT_NEAR(smallest_angle({0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}), 60 * deg, 1e-14);
  EXPECT_NEAR(smallest_angle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}), 45 * deg, 1e-14);
  // A needle: apex angle 2 atan(0.01 / 1).
  EXPECT_NEAR(smallest_angle({0, 0, 0}, {0, 0.02, 0}, {1, 0.01, 0}), 2 * std::atan(0.01), 1e-14);
  EXPECT_NEAR(corner_angle({0, 0, 0}, {1, 0, 0}, {-1, 1e-9, 0}), M_PI - 1e-9, 1e-14);
}
