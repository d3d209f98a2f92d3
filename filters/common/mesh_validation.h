// Checks every core runs first, so bad input fails with a clear message
// before any work (and before the host mesh is touched).
#pragma once

#include "common/tri_mesh.h"

namespace mr {

/// \throw InvalidInput if the mesh has no vertices, no faces (a point cloud),
///        deleted elements, or non-finite coordinates. `what` names the input
///        in the message ("the input mesh", "body 3", ...).
void require_triangle_surface(const TriMesh& mesh, const std::string& what = "the input mesh");

/// True if every coordinate of every vertex is finite.
bool has_finite_coordinates(const TriMesh& mesh);

/// Faces whose three vertices another face already has (in any order or orientation).
int count_duplicate_faces(const TriMesh& mesh);

/// \throw InvalidInput if some faces repeat another face's three vertices: a double
///        layer of zero thickness, whose every edge is non-manifold.
void require_no_duplicate_faces(const TriMesh& mesh, const std::string& what = "the input mesh");

/// \throw InvalidInput if every face has zero area (no surface to work on).
void require_some_area(const TriMesh& mesh, const std::string& what = "the input mesh");

}  // namespace mr
