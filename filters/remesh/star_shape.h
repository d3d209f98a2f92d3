// The shape of the faces around one point, as the smoothing moves measure it before and
// after they move the point: its smallest angle, and whether a face turned over.
#pragma once

#include "remesh/face_rings.h"
#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <array>
#include <vector>

namespace mr::remesh {

/// Smallest angle (radians) of the faces around point v; 1e9 when it has none.
inline double star_min_angle(const std::vector<Point3>& points, const std::vector<std::array<int, 3>>& faces,
                             const FaceRings& rings, int v) {
  double worst = 1e9;
  for (int k = rings.begin[v]; k < rings.begin[v + 1]; ++k) worst = std::min(worst, min_angle(points, faces[rings.item[k]]));
  return worst;
}

/// Some face around point v turns more than 60 degrees away from `normal` (unit: the normal
/// of the input face the point lies on), i.e. the move folded the surface.
inline bool star_folded(const std::vector<Point3>& points, const std::vector<std::array<int, 3>>& faces,
                        const FaceRings& rings, int v, const Point3& normal) {
  for (int k = rings.begin[v]; k < rings.begin[v + 1]; ++k) {
    const auto& f = faces[rings.item[k]];
    if (unit_normal(points[f[0]], points[f[1]], points[f[2]]) * normal < 0.5) return true;
  }
  return false;
}

}  // namespace mr::remesh
