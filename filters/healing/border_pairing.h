// Steps 1-3 of the healing: which border vertices and edges of the patches
// belong together. T-junctions are resolved here by splitting edges, so the
// soup changes; nothing moves yet.
#pragma once

#include "healing/soup.h"

#include <array>
#include <vector>

namespace mr::healing {

struct Pairing {
  std::vector<int> weld_class;                 ///< per vertex: representative of its weld class
  std::vector<std::array<int, 2>> seam_edges;  ///< vertex pairs of every welded border edge (one per pair)
  int border_edges = 0;                        ///< before healing
  int pairs = 0;
  int rejected = 0;                            ///< paired by vertices, failed the edge tolerance
  int t_junctions = 0;
};

/// Pairs the border edges of `soup` within the tolerances, splitting border
/// edges at T-junctions first. Vertices of one edge never join one class.
Pairing pair_borders(Soup& soup, double vertex_tolerance, double edge_tolerance);

}  // namespace mr::healing
