#include "union/point_table.h"

#include <cstring>

namespace mr::surface_union {

size_t PointTable::KeyHash::operator()(const Key& k) const {
  uint64_t h = 1469598103934665603ull;
  for (double v : {k.x, k.y, k.z}) {
    if (v == 0) v = 0;  // -0 and +0 are the same point
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    h = (h ^ bits) * 1099511628211ull;
    h ^= h >> 29;
  }
  return size_t(h);
}

int PointTable::insert(QPoint&& p) {
  Key key{p.d[0] == 0 ? 0.0 : p.d[0], p.d[1] == 0 ? 0.0 : p.d[1], p.d[2] == 0 ? 0.0 : p.d[2]};
  auto& bucket = index_[key];
  for (int i : bucket)
    if (same_point(points_[i], p)) return i;
  points_.push_back(std::move(p));
  bucket.push_back(int(points_.size()) - 1);
  return int(points_.size()) - 1;
}

}  // namespace mr::surface_union
