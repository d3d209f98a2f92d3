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

/// The face sides {face, side} on one edge (side z runs from corner z to z+1).
struct SideSpan {
  const std::array<int, 2>* first = nullptr;
  int count = 0;
  size_t size() const { return size_t(count); }
  const std::array<int, 2>& operator[](size_t k) const { return first[k]; }
  const std::array<int, 2>* begin() const { return first; }
  const std::array<int, 2>* end() const { return first + count; }
};

/// One undirected edge with the face sides on it.
struct SoupEdge {
  int v0, v1;  ///< v0 < v1
  SideSpan sides;
};

/// Every undirected edge, sorted by (v0, v1); the sides live in one flat
/// array (no allocation per edge). Move-only: the spans point into it.
class SoupEdges {
public:
  SoupEdges() = default;
  SoupEdges(SoupEdges&&) = default;
  SoupEdges& operator=(SoupEdges&&) = default;
  SoupEdges(const SoupEdges&) = delete;
  SoupEdges& operator=(const SoupEdges&) = delete;

  size_t size() const { return edges_.size(); }
  const SoupEdge& operator[](size_t e) const { return edges_[e]; }
  std::vector<SoupEdge>::const_iterator begin() const { return edges_.begin(); }
  std::vector<SoupEdge>::const_iterator end() const { return edges_.end(); }

private:
  friend SoupEdges soup_edges(const Soup& s);
  std::vector<SoupEdge> edges_;
  std::vector<std::array<int, 2>> sides_;
};

/// Every undirected edge of the soup: deterministic and O(N log N).
SoupEdges soup_edges(const Soup& s);

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
