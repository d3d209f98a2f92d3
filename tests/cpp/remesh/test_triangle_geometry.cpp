#include "remesh/triangle_geometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace mr;
using namespace mr::remesh;

namespace {

double smallest_corner_angle(const Point3& a, const Point3& b, const Point3& c) {
  return std::min({corner_angle(a, b, c), corner_angle(b, c, a), corner_angle(c, a, b)});
}

}  // namespace

// min_angle takes the arc tangent of the corners whose cotangent is largest only: it must give
// the smallest of the three corner angles bit for bit, on triangles of every shape, including
// the nearly isosceles and equilateral ones where two corners tie within rounding.
TEST(TriangleGeometry, MinAngleIsTheSmallestCornerAngleBitForBit) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> shape(0, 5);
  long ties = 0;
  for (int i = 0; i < 200000; ++i) {
    Point3 a(unit(rng), unit(rng), unit(rng)), b(unit(rng), unit(rng), unit(rng)), c;
    const Point3 mid = (a + b) / 2, side = b - a;
    const Point3 across = Point3(-side[1], side[0], 0.3 * side[2]);
    switch (shape(rng)) {
      case 0: c = Point3(unit(rng), unit(rng), unit(rng)); break;            // any
      case 1: c = mid + across * (1e-9 * unit(rng)); break;                  // a cap, nearly flat
      case 2: c = a + (b - a) * 1e-12 + across * unit(rng); break;           // a needle
      case 3: c = mid + across * (0.8660254037844386 + 1e-15 * unit(rng)); break;  // nearly equilateral
      case 4: c = mid + across * unit(rng); break;                           // isosceles
      default: c = a; break;                                                 // a side without length
    }
    const double fast = min_angle(a, b, c), plain = smallest_corner_angle(a, b, c);
    ASSERT_EQ(fast, plain) << "triangle " << i;
    ties += std::fabs(corner_angle(c, a, b) - corner_angle(a, b, c)) < 1e-12;
  }
  EXPECT_GT(ties, 1000);  // the isosceles shapes did put two corners within rounding
}
