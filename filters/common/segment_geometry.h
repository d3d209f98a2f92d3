// Point-to-segment measures (healing's border pairing and gap report, the remesher's lines).
#pragma once

#include "common/tri_mesh.h"

#include <algorithm>

namespace mr {

/// Parameter t of the projection of p on the line a + t (b - a) (0 for a point segment).
inline double segment_param(const Point3& p, const Point3& a, const Point3& b) {
  const Point3 d = b - a;
  const double len2 = d.SquaredNorm();
  return len2 > 0 ? ((p - a) * d) / len2 : 0.0;
}

inline double point_segment_distance(const Point3& p, const Point3& a, const Point3& b) {
  const double t = std::clamp(segment_param(p, a, b), 0.0, 1.0);
  return vcg::Distance(p, a + (b - a) * t);
}

}  // namespace mr
