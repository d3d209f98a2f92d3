// A sparse uniform grid over 3D boxes: items are stored in every cell their
// box overlaps, so a query near a point visits only a few cells. Used for
// "everything within tolerance" searches, which stay O(N) when the cell size
// is at least the search radius.
#pragma once

#include "common/tri_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace mr {

class UniformGrid {
public:
  explicit UniformGrid(double cell) : cell_(cell > 0 ? cell : 1.0) {}

  double cell_size() const { return cell_; }

  /// Stores `item` in every cell overlapped by the box [lo, hi].
  void insert(int item, const Point3& lo, const Point3& hi) {
    const auto a = cell_of(lo), b = cell_of(hi);
    for (int64_t x = a[0]; x <= b[0]; ++x)
      for (int64_t y = a[1]; y <= b[1]; ++y)
        for (int64_t z = a[2]; z <= b[2]; ++z) cells_[key(x, y, z)].push_back(item);
  }

  void insert(int item, const Point3& p) { insert(item, p, p); }

  /// Stores `item` in every cell within `pad` of the segment (and a few more): the segment
  /// in pieces no longer than a cell, each by its box grown by `pad`. The whole segment's
  /// box would fill (length / cell)^3 cells: a 30-triangle soup with a tolerance-sized cell
  /// took minutes (fuzz_filters.py seed 863). Costs about length / cell pieces of 8 cells.
  void insert_segment(int item, const Point3& a, const Point3& b, double pad) {
    const int pieces = int(std::min(1e6, std::max(1.0, std::ceil((b - a).Norm() / cell_))));
    for (int k = 0; k < pieces; ++k) {
      const Point3 p = a + (b - a) * (double(k) / pieces), q = k + 1 == pieces ? b : a + (b - a) * (double(k + 1) / pieces);
      const Point3 lo(std::min(p[0], q[0]) - pad, std::min(p[1], q[1]) - pad, std::min(p[2], q[2]) - pad);
      const Point3 hi(std::max(p[0], q[0]) + pad, std::max(p[1], q[1]) + pad, std::max(p[2], q[2]) + pad);
      insert_once(item, lo, hi);
    }
  }

  /// Calls f(item) for every item stored in a cell overlapped by the box
  /// [p - r, p + r]; an item may be reported more than once.
  template <class F>
  void visit(const Point3& p, double r, F&& f) const {
    const auto a = cell_of(p - Point3(r, r, r)), b = cell_of(p + Point3(r, r, r));
    for (int64_t x = a[0]; x <= b[0]; ++x)
      for (int64_t y = a[1]; y <= b[1]; ++y)
        for (int64_t z = a[2]; z <= b[2]; ++z) {
          auto it = cells_.find(key(x, y, z));
          if (it == cells_.end()) continue;
          for (int item : it->second) f(item);
        }
  }

private:
  /// insert(), skipping cells whose last item is this one already (consecutive pieces of
  /// a segment share cells).
  void insert_once(int item, const Point3& lo, const Point3& hi) {
    const auto a = cell_of(lo), b = cell_of(hi);
    for (int64_t x = a[0]; x <= b[0]; ++x)
      for (int64_t y = a[1]; y <= b[1]; ++y)
        for (int64_t z = a[2]; z <= b[2]; ++z) {
          auto& items = cells_[key(x, y, z)];
          if (items.empty() || items.back() != item) items.push_back(item);
        }
  }

  std::array<int64_t, 3> cell_of(const Point3& p) const {
    return {int64_t(std::floor(p[0] / cell_)), int64_t(std::floor(p[1] / cell_)),
            int64_t(std::floor(p[2] / cell_))};
  }
  static uint64_t key(int64_t x, int64_t y, int64_t z) {
    // 21 bits per axis: coordinates are relative to cell size, so wrap-around
    // only merges far-apart cells, which costs time, never correctness.
    const uint64_t m = (uint64_t(1) << 21) - 1;
    return (uint64_t(x) & m) | ((uint64_t(y) & m) << 21) | ((uint64_t(z) & m) << 42);
  }

  double cell_;
  std::unordered_map<uint64_t, std::vector<int>> cells_;
};

}  // namespace mr
