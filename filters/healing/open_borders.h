// Step 6 of the healing: what stays open, and how wide the gaps still are.
#pragma once

#include "healing/soup.h"

#include <array>
#include <vector>

namespace mr::healing {

struct OpenBorders {
  int edges = 0;
  int loops = 0;
  int gaps = 0;              ///< open edges facing another open border within the search radius
  double largest_gap = 0;
  std::vector<std::array<bool, 3>> side_open;  ///< per face side
};

/// Boundary edges of the welded soup. A boundary edge whose midpoint lies
/// within `search_radius` of another, roughly parallel boundary edge that
/// shares no vertex with it is a gap left open; its width is that distance.
OpenBorders find_open_borders(const Soup& soup, const EdgeTable& edges, double search_radius);

}  // namespace mr::healing
