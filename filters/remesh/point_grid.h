// Points in a hash grid of cubic cells, for the advancing front's "which front points are
// near" questions. Entries are never removed; callers skip points off the front.
#pragma once

#include "common/tri_mesh.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <unordered_map>
#include <vector>

namespace mr::remesh {

class PointGrid {
public:
  explicit PointGrid(double cell) : cell_(cell) {}
  void add(int id, const Point3& p) {
    const auto c = coords(p);
    Cell& cell = cells_[pack(c[0], c[1], c[2])];
    cell.at = c;
    cell.ids.push_back(id);
  }
  template <class F> void for_each_near(const Point3& p, double r, F&& f) const {
    const long n = long(std::ceil(r / cell_));
    const auto c = coords(p);
    auto within = [&](const std::array<long, 3>& at) {
      return std::abs(at[0] - c[0]) <= n && std::abs(at[1] - c[1]) <= n && std::abs(at[2] - c[2]) <= n;
    };
    // A box of more cells than the grid holds (a side many elements long, left by a damaged
    // front: armadillo at 1% with min_line_length 2% had one 20 x target, whose box of 561^3
    // cells took 20 s): the filled cells are visited instead, the same ones.
    if (double(2 * n + 1) * double(2 * n + 1) * double(2 * n + 1) > double(cells_.size())) {
      for (const auto& [key, cell] : cells_)
        if (within(cell.at))
          for (int id : cell.ids) f(id);
      return;
    }
    for (long i = c[0] - n; i <= c[0] + n; ++i)
      for (long j = c[1] - n; j <= c[1] + n; ++j)
        for (long k = c[2] - n; k <= c[2] + n; ++k) {
          auto it = cells_.find(pack(i, j, k));
          if (it == cells_.end() || !within(it->second.at)) continue;
          for (int id : it->second.ids) f(id);
        }
  }

private:
  struct Cell {
    std::array<long, 3> at;
    std::vector<int> ids;
  };
  std::array<long, 3> coords(const Point3& p) const {
    return {long(std::floor(p[0] / cell_)), long(std::floor(p[1] / cell_)), long(std::floor(p[2] / cell_))};
  }
  static std::int64_t pack(long i, long j, long k) {
    return (std::int64_t(i & 0x1FFFFF) << 42) | (std::int64_t(j & 0x1FFFFF) << 21) | std::int64_t(k & 0x1FFFFF);
  }
  double cell_;
  std::unordered_map<std::int64_t, Cell> cells_;
};

}  // namespace mr::remesh
