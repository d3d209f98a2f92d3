// Disjoint sets over 0..n-1 with path halving, for connected components and welds.
#pragma once

#include <numeric>
#include <utility>
#include <vector>

namespace mr {

class UnionFind {
public:
  explicit UnionFind(int n) : parent_(static_cast<size_t>(n)) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int a) {
    while (parent_[size_t(a)] != a) a = parent_[size_t(a)] = parent_[size_t(parent_[size_t(a)])];
    return a;
  }
  /// Joins the sets; the smaller root index stays root (deterministic).
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (b < a) std::swap(a, b);
    parent_[size_t(b)] = a;
  }
  void grow(int n) {
    for (int i = int(parent_.size()); i < n; ++i) parent_.push_back(i);
  }

private:
  std::vector<int> parent_;
};

}  // namespace mr
