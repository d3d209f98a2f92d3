// Points in a grid of cubic cells, for the advancing front's "which front points are near"
// questions. Entries are never removed; callers skip points off the front.
#pragma once

#include "common/flat_index_map.h"
#include "common/tri_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace mr::remesh {

class PointGrid {
public:
  explicit PointGrid(double cell) : cell_(cell) {}
  void add(int id, const Point3& p) {
    const auto c = coords(p);
    const auto [index, added] = column_index_.emplace(pack(c[0], c[1]), int(columns_.size()));
    if (added) columns_.emplace_back();
    std::vector<Cell>& column = columns_[size_t(index)];
    auto it = std::lower_bound(column.begin(), column.end(), c[2], [](const Cell& x, long k) { return x.at[2] < k; });
    if (it == column.end() || it->at[2] != c[2]) it = column.insert(it, Cell{c, {}});
    it->ids.push_back(id);
  }
  /// Calls f(id) for the points in the cells within ceil(r / cell) cells of p's on every axis,
  /// in no particular order.
  template <class F> void for_each_near(const Point3& p, double r, F&& f) const {
    const long n = long(std::ceil(r / cell_));
    const auto c = coords(p);
    // A box of more columns than the grid holds (a side many elements long, left by a damaged
    // front: armadillo at 1% with min_line_length 2% had one 20 x target, whose box of 561^3
    // cells took 20 s): the filled columns are visited instead, the same cells.
    if (double(2 * n + 1) * double(2 * n + 1) > double(columns_.size())) {
      for (const auto& column : columns_) visit_column(column, c, n, f);
      return;
    }
    // Columns along z, each sorted by z: a query looks up (2n + 1)^2 columns, not (2n + 1)^3
    // mostly empty cells (the lookups were a tenth of box.STL's regrid).
    for (long i = c[0] - n; i <= c[0] + n; ++i)
      for (long j = c[1] - n; j <= c[1] + n; ++j)
        if (const int* index = column_index_.find(pack(i, j))) visit_column(columns_[size_t(*index)], c, n, f);
  }

private:
  struct Cell {
    std::array<long, 3> at;
    std::vector<int> ids;
  };
  template <class F>
  static void visit_column(const std::vector<Cell>& column, const std::array<long, 3>& c, long n, F&& f) {
    if (column.empty() || std::abs(column.front().at[0] - c[0]) > n || std::abs(column.front().at[1] - c[1]) > n) return;
    auto it = std::lower_bound(column.begin(), column.end(), c[2] - n, [](const Cell& x, long k) { return x.at[2] < k; });
    for (; it != column.end() && it->at[2] <= c[2] + n; ++it)
      for (int id : it->ids) f(id);
  }
  std::array<long, 3> coords(const Point3& p) const {
    return {long(std::floor(p[0] / cell_)), long(std::floor(p[1] / cell_)), long(std::floor(p[2] / cell_))};
  }
  static std::uint64_t pack(long i, long j) { return (std::uint64_t(std::uint32_t(i)) << 32) | std::uint32_t(j); }
  double cell_;
  FlatIndexMap<std::uint64_t> column_index_;  // (x, y) cell -> index in columns_
  std::vector<std::vector<Cell>> columns_;
};

}  // namespace mr::remesh
