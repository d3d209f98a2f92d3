// Post-generation surface recovery (Löhner 1996, section 4): free points, which lie on
// the flat input triangles, are moved onto a smoother surface through the input
// vertices. Line and corner points never move, so feature lines stay exact.
#pragma once

#include "remesh/output_mesh.h"
#include "remesh/remesh.h"
#include "remesh/surface_locator.h"

#include <array>

namespace mr::remesh {

/// Unit vertex normals per face corner, averaged (area-weighted) over the faces of the same
/// group only, so normals do not blend across ridges.
std::vector<std::array<Point3, 3>> corner_normals(const Surface& surface);

/// Point at barycentric `l` of the quadratic triangle through the corners of face f, with
/// Hermite mid-side points from the corner normals.
Point3 quadratic_point(const Surface& surface, const std::vector<std::array<Point3, 3>>& normals, int f,
                       const std::array<double, 3>& l);

/// Point at barycentric `l` of the cubic (PN) triangle built from the corner positions and normals.
Point3 cubic_point(const Surface& surface, const std::vector<std::array<Point3, 3>>& normals, int f,
                   const std::array<double, 3>& l);

/// Applies the recovery to every free point of `out`; returns the number of points moved.
int recover_surface(OutputMesh& out, const Surface& surface, Recovery mode);

}  // namespace mr::remesh
