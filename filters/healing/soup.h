// The working representation of the healing steps: indexed triangles that
// change as edges split and vertices weld, with their edges rebuilt on demand.
#pragma once

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

/// One undirected edge with the face sides on it (side z runs from corner z to z+1).
struct SoupEdge {
  int v0, v1;                        ///< v0 < v1
  std::vector<std::array<int, 2>> sides;  ///< {face, side}
};

/// Every undirected edge, sorted by (v0, v1): deterministic and O(N log N).
std::vector<SoupEdge> soup_edges(const Soup& s);

/// Vertex neighbours through edges, sorted.
std::vector<std::vector<int>> vertex_neighbours(const Soup& s);

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
