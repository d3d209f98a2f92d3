// Closest point of a triangle to a point: the remesher's host-face search and the union's
// deviation checks both need it.
#pragma once

#include "common/tri_mesh.h"

#include <array>

namespace mr {

/// Closest point of triangle (a,b,c) to p; `bary` receives its barycentric coordinates.
/// A degenerate triangle gives its nearest corner.
Point3 closest_point_on_triangle(const Point3& p, const Point3& a, const Point3& b, const Point3& c,
                                 std::array<double, 3>& bary);

}  // namespace mr
