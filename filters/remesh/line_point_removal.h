// Removal of feature-line points where their faces are bad and the line does not need them.
// The size field shrinks near short lines and close corners, so a short line between two
// corners can get a point in its middle although the patch beside it is one small triangle
// whose best shape is the triangle itself (rabbit.obj united, regridded at 1%: a 0.036 line
// split in two left 5.7 and 6.6-degree faces where the patch's own corners allow 12.3). Such a
// point collapses onto one of its two neighbours on the line: the two segments become one.
#pragma once

#include "remesh/line_sliding.h"
#include "remesh/output_mesh.h"
#include "remesh/size_field.h"
#include "remesh/surface_locator.h"

#include <array>
#include <vector>

namespace mr::remesh {

/// Removes slidable points of `paths` whose faces have a smallest angle under `worse_than_rad`,
/// each by collapsing it onto a neighbour on its line, when that raises the smallest angle of
/// its faces, the link condition holds, no face turns by more than acos(0.7), the merged segment
/// stays within 0.05 x size of the input polyline (and of the removed point) and no new edge is
/// longer than 1.4 x size. `paths` and `feature_edges` follow; removed points stay in
/// `out.points`, used by no face. Returns the points the removed ones collapsed onto.
std::vector<int> remove_line_points(OutputMesh& out, std::vector<LinePath>& paths,
                                    std::vector<std::array<int, 2>>& feature_edges, const SurfaceLocator& locator,
                                    const SizeField& size, double worse_than_rad);

}  // namespace mr::remesh
