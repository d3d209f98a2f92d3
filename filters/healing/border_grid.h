// The cell size of a uniform grid that files border edges as segments.
#pragma once

#include "healing/soup.h"

#include <algorithm>
#include <vector>

namespace mr::healing {

/// At least `tol`, the edges' mean length and a 64th of the longest. insert_segment files a
/// segment in pieces of a cell, so a tolerance-sized cell made long edges cost
/// (length / tolerance) pieces each (fuzz_filters.py seed 863 took 298 s).
inline double border_grid_cell(const Soup& s, const EdgeTable& edges, const std::vector<int>& list, double tol) {
  double mean_len = 0, max_len = 0;
  for (int e : list) {
    const double l = vcg::Distance(s.pos[edges.v0(e)], s.pos[edges.v1(e)]);
    mean_len += l / double(list.size());
    max_len = std::max(max_len, l);
  }
  return std::max({tol, mean_len, max_len / 64});
}

}  // namespace mr::healing
