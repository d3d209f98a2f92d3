// The working representation of the healing steps: indexed triangles that
// change as edges split and vertices weld, with their edges rebuilt on demand.
#pragma once

#include "common/edge_table.h"
#include "common/tri_mesh.h"
#include "common/union_find.h"

#include <array>
#include <numeric>
#include <vector>

namespace mr::healing {

struct Soup {
  std::vector<Point3> pos;
  std::vector<std::array<int, 3>> tri;
  std::vector<int> patch;  ///< per triangle
};

/// Every undirected edge of the soup (degenerate sides left out): deterministic and O(N).
inline EdgeTable soup_edges(const Soup& s) { return EdgeTable(s.pos.size(), s.tri); }

}  // namespace mr::healing
