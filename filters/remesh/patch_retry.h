// What a patch's front left behind, and taking it back: a patch whose front could not close
// (unmeshed sides) or pinched a point (its faces around it form two fans, a non-manifold
// vertex) is meshed again with smaller elements, which pass thin parts of the surface.
#pragma once

#include "remesh/output_mesh.h"

#include <vector>

namespace mr::remesh {

/// Points where the faces of `patch` make more than one fan (non-manifold vertices), ascending:
/// free points with two fans or more, line and corner points with two or more of which one
/// closes all round the point (elsewhere a patch may border a line or corner point twice).
std::vector<int> pinched_points(const OutputMesh& out, int patch);

/// Patches (ascending) with two faces on a segment of `feature_edges` that has more than two:
/// an edge of their own that the line's patches also took.
std::vector<int> patches_on_taken_lines(const OutputMesh& out, const std::vector<std::array<int, 2>>& feature_edges);

/// Removes the faces of `patch` (its points stay, unused) and the shared edges only they used.
void remove_patch_faces(OutputMesh& out, int patch);

}  // namespace mr::remesh
