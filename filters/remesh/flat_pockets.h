// Two output faces on the same three points, facing opposite ways: a pocket meshed flat. Where
// a patch folds back over itself along a thin stretch, its front can close the same triangle
// once from each side of the fold (box.STL united, regridded at 1%: two corners and a line
// point). The pair encloses nothing, and it pinches the surface at its corners: they become
// non-manifold vertices.
#pragma once

#include "remesh/output_mesh.h"

namespace mr::remesh {

/// Removes every such pair from `out` (faces and their patches; shared edges rebuilt).
/// Returns the number of pairs removed.
int remove_flat_pockets(OutputMesh& out);

}  // namespace mr::remesh
