// Step 4 of the healing: paired borders move to their average and weld.
#pragma once

#include "healing/soup.h"

#include <array>
#include <vector>

namespace mr::healing {

struct Welded {
  Soup soup;                                   ///< compact: only referenced vertices
  std::vector<double> move;                    ///< per output vertex
  std::vector<int> new_index;                  ///< per input vertex (-1 if dropped)
  int duplicate_faces_removed = 0;
  int degenerate_faces_removed = 0;
};

/// Every weld class moves to the mean of its members (for two borders the
/// midpoint of each vertex pair; where n patches meet, the mean of the n
/// corners) and becomes one vertex. Faces that collapse or duplicate another
/// face (two patches overlapping face for face) are dropped.
Welded weld_classes(const Soup& soup, const std::vector<int>& weld_class);

}  // namespace mr::healing
