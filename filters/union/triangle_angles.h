// Angles of triangles in 3D, for the quality decisions of the sliver step.
#pragma once

#include "union/vec3.h"

#include <cmath>

namespace mr::surface_union {

/// Angle at o between the directions to p and q, in radians.
inline double corner_angle(const V3& o, const V3& p, const V3& q) {
  const V3 u = sub3(p, o), w = sub3(q, o);
  return std::atan2(norm(cross(u, w)), dot(u, w));
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
