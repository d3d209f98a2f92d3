// Broad phase: pairs of faces of different bodies whose bounding boxes overlap,
// found through a uniform grid so the cost follows the overlap, not |A| x |B|.
#pragma once

#include "union/soup.h"

#include <utility>
#include <vector>

namespace mr::surface_union {

/// Face pairs (f, g), f < g, body[f] != body[g], closed bounding boxes overlapping.
std::vector<std::pair<int, int>> candidate_pairs(const Soup& soup);

}  // namespace mr::surface_union
