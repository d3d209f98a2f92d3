// The shape of the faces around one point, as the smoothing moves measure it before and
// after they move the point: its smallest angle, and whether a face turned over.
#pragma once

#include "remesh/face_rings.h"
#include "remesh/triangle_geometry.h"
#include "remesh/wedge_tips.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_set>
#include <vector>

namespace mr::remesh {

/// Mean length of the edges from point v to the other corners of its faces (each edge once per
/// face it bounds); 0 when it has none. The reach of a point's search for a better place.
inline double mean_ring_edge(const std::vector<Point3>& points, const std::vector<std::array<int, 3>>& faces,
                             const FaceRings& rings, int v) {
  double edge = 0;
  int count = 0;
  for (int k = rings.begin[v]; k < rings.begin[v + 1]; ++k)
    for (int x : faces[rings.item[k]])
      if (x != v) { edge += (points[x] - points[v]).Norm(); ++count; }
  return count > 0 ? edge / count : 0.0;
}

/// Smallest angle (radians) of the faces around point v; 1e9 when it has none.
inline double star_min_angle(const std::vector<Point3>& points, const std::vector<std::array<int, 3>>& faces,
                             const FaceRings& rings, int v) {
  double worst = 1e9;
  for (int k = rings.begin[v]; k < rings.begin[v + 1]; ++k) worst = std::min(worst, min_angle(points, faces[rings.item[k]]));
  return worst;
}

/// The smallest angles (radians) of the faces around point v: at their wedge tips (wedge_tips.h)
/// and at every other corner; 1e9 where there is none.
struct StarAngles {
  double tips = 1e9, off_wedges = 1e9;
  double smallest() const { return std::min(tips, off_wedges); }
};
inline StarAngles star_angles(const std::vector<Point3>& points, const std::vector<std::array<int, 3>>& faces,
                              const FaceRings& rings, int v, const std::unordered_set<std::uint64_t>& feature_keys) {
  StarAngles s;
  for (int k = rings.begin[v]; k < rings.begin[v + 1]; ++k) {
    const auto& f = faces[rings.item[k]];
    for (int z = 0; z < 3; ++z) {
      const int a = f[z], b = f[(z + 1) % 3], c = f[(z + 2) % 3];
      const double angle = corner_angle(points[a], points[b], points[c]);
      double& worst = is_wedge_tip(angle, a, b, c, feature_keys) ? s.tips : s.off_wedges;
      worst = std::min(worst, angle);
    }
  }
  return s;
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
