// Smoothing aimed at the smallest angle. The Laplacian smoothing moves a free point to the
// centre of its ring, which cannot lift a face pinched between feature points: the face's
// small angle sits at a line point, and only the free corner across from it can open it, by
// moving away from the line rather than to the centre. Here a free point whose faces stay
// under the goal searches the input nearby for the place where their smallest angle is largest.
#pragma once

#include "remesh/output_mesh.h"
#include "remesh/surface_locator.h"

#include <vector>

namespace mr::remesh {

/// Moves each free point of `movable` whose faces' smallest angle is under `goal_rad` to the
/// place nearby on the input (in its patch) where that angle is largest: a compass search in
/// the point's tangent plane, every place projected onto the input. A move is kept only if it
/// raises the smallest angle and folds no face, so the mesh's minimum angle never drops.
/// Returns the points moved, in the order they moved.
std::vector<int> raise_pinched_free_points(OutputMesh& out, const SurfaceLocator& locator,
                                           const std::vector<char>& movable, double goal_rad);

}  // namespace mr::remesh
