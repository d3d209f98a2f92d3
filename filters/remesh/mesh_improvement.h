// A short post-pass that only improves (Löhner 1996, section 3.6): edge swaps and
// smoothing of free points projected back onto the input. Angle swaps and smoothing raise
// the smallest angle of the faces they touch; valence swaps (towards 6 neighbours) keep
// their faces above 35 degrees or their old smallest angle, so the mesh's minimum angle
// never drops. Then free points move, or go at short edges, for edge lengths within
// [0.7, 1.4] x the size while their faces stay above 30 degrees or their old smallest angle
// (length_equalisation.h). Feature edges are never swapped, corners never move and line points
// only slide along their lines (line_sliding.h) or go where their line does not need them
// (line_point_removal.h).
#pragma once

#include "remesh/line_sliding.h"
#include "remesh/output_mesh.h"
#include "remesh/size_field.h"
#include "remesh/surface_locator.h"

#include <array>
#include <vector>

namespace mr::remesh {

struct ImprovementResult {
  int swaps = 0;
  int moves = 0;
  int collapsed = 0;  ///< free points removed by collapsing a short edge
  int split = 0;      ///< long edges split at their middle
  int line_points_removed = 0;  ///< line points whose two segments became one (line_point_removal.h)
  int relaxed_wedges = 0;       ///< wedge tips whose lines now share their first segment (wedge_relaxing.h)
  int closed_line_gaps = 0;     ///< points where lines that passed close now meet (wedge_relaxing.h)
  int jointly_moved = 0;        ///< points moved by the joint search around faces under the goal (joint_polish.h)
};

/// `feature_edges` are output edges that must stay (either orientation); the points of
/// `line_paths` slide along them or, where the line does not need them, go (none given: line
/// points stay); `feature_edges` then follow. `moved`: points just moved
/// (snapped onto input vertices) that must stay there; the pass then works only within two edges
/// of them, the rest having had its pass already (empty: the whole mesh). `relax_wedges`: the
/// lines at wedge tips may share their first segment (wedge_relaxing.h).
ImprovementResult improve_mesh(OutputMesh& out, std::vector<std::array<int, 2>>& feature_edges,
                               const SurfaceLocator& locator, const SizeField& size, int iterations,
                               std::vector<LinePath> line_paths = {}, const std::vector<int>& moved = {},
                               bool relax_wedges = false);

}  // namespace mr::remesh
