// Angles of triangles in 3D, for the quality decisions of the sliver step.
#pragma once

#include "union/face_clearance.h"

#include <cmath>

namespace mr::surface_union {

/// Angle at o between the directions to p and q, in radians.
inline double corner_angle(const V3& o, const V3& p, const V3& q) {
  const V3 u{p[0] - o[0], p[1] - o[1], p[2] - o[2]}, w{q[0] - o[0], q[1] - o[1], q[2] - o[2]};
  const V3 c{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
  return std::atan2(std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), u[0] * w[0] + u[1] * w[1] + u[2] * w[2]);
}

/// Smallest angle of triangle abc, in radians. It lies opposite the shortest side: one atan2
/// instead of three.
inline double smallest_angle(const V3& a, const V3& b, const V3& c) {
  auto squared = [](const V3& p, const V3& q) {
    return (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) + (q[2] - p[2]) * (q[2] - p[2]);
  };
  const double lab = squared(a, b), lbc = squared(b, c), lca = squared(c, a);
  if (lab <= lbc && lab <= lca) return corner_angle(c, a, b);
  if (lbc <= lca) return corner_angle(a, b, c);
  return corner_angle(b, c, a);
}

}  // namespace mr::surface_union
