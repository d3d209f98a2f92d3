// Best triangulation of a small polygon (the link of a vertex being removed): the one
// whose smallest angle is largest, among those whose triangles all turn the polygon's
// way seen from a given direction. Interval dynamic programming, O(k^3) for k corners.
#pragma once

#include "union/face_clearance.h"

#include <array>
#include <functional>
#include <vector>

namespace mr::surface_union {

/// ring: the polygon's corners in order, counter-clockwise seen from `up`.
/// allowed(i, j): whether diagonal (i, j) (i < j, not a polygon side) may be used.
/// forced: a diagonal every triangulation must contain ({-1, -1}: none); diagonals
/// crossing it are not considered.
/// On success `out` holds k - 2 triangles (indices into ring, oriented like the polygon)
/// and `min_angle` their smallest angle (radians, measured in 3D). Fails as well when no
/// triangulation has a smallest angle above `must_exceed` (which then prunes the search).
bool best_polygon_triangulation(const std::vector<V3>& ring, const V3& up, const std::function<bool(int, int)>& allowed,
                                std::array<int, 2> forced, std::vector<std::array<int, 3>>& out, double& min_angle,
                                double must_exceed = -1);

}  // namespace mr::surface_union
