// Angles of triangles in 3D, for the quality decisions of the sliver step.
#pragma once

#include "union/vec3.h"

#include <cmath>

namespace mr::surface_union {

/// atan2(y, x) for y >= 0, within a few ulps of the library's. The sliver step takes
/// angles of candidate faces a few hundred thousand times on CAD plates, and the
/// library's atan2 was a tenth of its instructions there. The ratio min/max in [0, 1]
/// is moved next to the nearest of tan(k pi/16), k = 0..4, by the addition formula,
/// leaving |s| < 0.099, where eight terms of atan's series are exact to 5e-18.
inline double angle_of(double y, double x) {
  const bool back = x < 0;
  const double ax = back ? -x : x;
  const bool steep = y > ax;
  const double num = steep ? ax : y, den = steep ? y : ax;
  if (!(den > 0 && den <= 1.7976931348623157e308)) return std::atan2(y, x);  // 0, infinite or NaN
  static constexpr double kTan[5] = {0.0, 0.198912367379658, 0.41421356237309503, 0.6681786379192989, 1.0};
  static constexpr double kAtan[5] = {0.0, 0.19634954084936207, 0.39269908169872414, 0.5890486225480862,
                                      0.7853981633974483};
  const double t = num / den;
  const int k = int(t > 0.09849140335716425) + int(t > 0.3033466836073424) + int(t > 0.5345111359507916) +
                int(t > 0.8206787908286602);
  const double c = kTan[k];
  const double s = (num - c * den) / (den + c * num);  // tan(atan(t) - atan(c))
  const double s2 = s * s;
  const double series =
      1 - s2 * (1.0 / 3 - s2 * (1.0 / 5 - s2 * (1.0 / 7 - s2 * (1.0 / 9 - s2 * (1.0 / 11 - s2 * (1.0 / 13 - s2 / 15))))));
  double a = kAtan[k] + s * series;
  if (steep) a = 1.5707963267948966 - a;
  if (back) a = 3.141592653589793 - a;
  return a;
}

/// Angle at o between the directions to p and q, in radians.
inline double corner_angle(const V3& o, const V3& p, const V3& q) {
  const V3 u = sub3(p, o), w = sub3(q, o);
  return angle_of(norm(cross(u, w)), dot(u, w));
}

/// Smallest angle of triangle abc, in radians. It lies opposite the shortest side: one atan2
/// instead of three.
inline double smallest_angle(const V3& a, const V3& b, const V3& c) {
  auto squared = [](const V3& p, const V3& q) {
    const V3 d = sub3(q, p);
    return dot(d, d);
  };
  const double lab = squared(a, b), lbc = squared(b, c), lca = squared(c, a);
  if (lab <= lbc && lab <= lca) return corner_angle(c, a, b);
  if (lbc <= lca) return corner_angle(a, b, c);
  return corner_angle(b, c, a);
}

}  // namespace mr::surface_union
