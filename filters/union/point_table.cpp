#include "union/point_table.h"

#include "union/vec3.h"

#include <algorithm>

namespace mr::surface_union {

size_t PointTable::KeyHash::operator()(const Key& k) const { return hash_position(k.x, k.y, k.z); }

int PointTable::insert(QPoint&& p) {
  Key key{p.d[0] == 0 ? 0.0 : p.d[0], p.d[1] == 0 ? 0.0 : p.d[1], p.d[2] == 0 ? 0.0 : p.d[2]};
  const int id = int(points_.size());
  const auto [first, added] = index_.emplace(key, id);
  if (!added) {
    int last = -1;
    for (int i = first; i >= 0; i = next_[i]) {
      if (same_point(points_[i], p)) return i;
      last = i;
    }
    next_[last] = id;
  }
  points_.push_back(std::move(p));
  next_.push_back(-1);
  line_.push_back({Line{-1, -1}, Line{-1, -1}});
  return id;
}

int PointTable::insert_on_line(QPoint&& p, int u, int w) {
  const int id = insert(std::move(p));
  mark_on_line(id, u, w);
  return id;
}

void PointTable::mark_on_line(int id, int u, int w) {
  if (id == u || id == w || u == w) return;
  const Line l{std::min(u, w), std::max(u, w)};
  for (auto& slot : line_[id]) {
    if (slot == l) return;
    if (slot[0] < 0) {
      slot = l;
      return;
    }
  }
}

bool PointTable::known_collinear(int a, int b, int c) const {
  const int p[3] = {a, b, c};
  for (int k = 0; k < 3; ++k)
    for (const Line& l : line_[p[k]]) {
      if (l[0] < 0) break;
      bool all = true;
      for (int m = 0; m < 3 && all; ++m) {
        const int x = p[m];
        all = m == k || x == l[0] || x == l[1] || x == p[k] || line_[x][0] == l || line_[x][1] == l;
      }
      if (all) return true;
    }
  return false;
}

}  // namespace mr::surface_union
