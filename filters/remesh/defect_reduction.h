// Removes valence defects that single edge swaps cannot: the irregular points the front leaves
// where fronts meet are mostly adjacent 5-7 pairs (dislocations), and two such pairs close
// together annihilate only through a short sequence of swaps (glides of a pair, each keeping the
// deviation, then one lowering it) whose faces are poor until the points around them move. So a
// sequence of up to four swaps that lowers the valence deviation is tried with the free points
// around it smoothed (projected onto the input) and kept only when its faces stay above
// min(their old smallest angle, `floor`) and their mean smallest angle barely drops; otherwise
// everything is undone.
#pragma once

#include "remesh/output_mesh.h"
#include "remesh/surface_locator.h"

#include <cstdint>
#include <unordered_set>
#include <vector>

namespace mr::remesh {

struct DefectReductionResult {
  int sequences = 0;  ///< swap sequences kept
  int swaps = 0;      ///< swaps in them
  int moves = 0;      ///< points the smoothing of kept sequences moved
  int tried = 0;      ///< sequences smoothed and judged
};

/// `fixed`: undirected edge keys (OutputMesh::edge_key) never swapped. Only sequences touching a
/// point of `region` are tried, and only free points of `movable` move. `floor` in radians.
DefectReductionResult reduce_valence_defects(OutputMesh& out, const std::unordered_set<std::uint64_t>& fixed,
                                             const SurfaceLocator& locator, const std::vector<char>& region,
                                             const std::vector<char>& movable, double floor);

}  // namespace mr::remesh
