// The working representation of the healing steps: indexed triangles that
// change as edges split and vertices weld, with their edges rebuilt on demand.
#pragma once

#include "common/edge_table.h"
#include "common/tri_mesh.h"

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

class UnionFind {
public:
  explicit UnionFind(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int a) {
    while (parent_[a] != a) a = parent_[a] = parent_[parent_[a]];
    return a;
  }
  /// Joins the sets; the smaller root index stays root (deterministic).
  void unite(int a, int b) {
    a = find(a); b = find(b);
    if (a == b) return;
    if (b < a) std::swap(a, b);
    parent_[b] = a;
  }
  void grow(int n) { for (int i = int(parent_.size()); i < n; ++i) parent_.push_back(i); }

private:
  std::vector<int> parent_;
};

}  // namespace mr::healing
