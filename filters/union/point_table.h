// The one table of exact points of a union run: input vertices and every
// constructed intersection point. A point is stored once, whatever computed it,
// because equal rationals are equal: neighbouring faces share vertices exactly.
#pragma once

#include "union/exact.h"

#include <unordered_map>
#include <vector>

namespace mr::surface_union {

class PointTable {
public:
  /// Index of `p`, adding it if no equal point is stored yet.
  int insert(QPoint&& p);
  const QPoint& operator[](int i) const { return points_[i]; }
  int size() const { return int(points_.size()); }

private:
  struct Key {
    double x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct KeyHash {
    size_t operator()(const Key& k) const;
  };
  std::vector<QPoint> points_;
  // Truncated doubles of the rationals: equal points have equal keys; the rare
  // distinct points with one key are told apart exactly.
  std::unordered_map<Key, std::vector<int>, KeyHash> index_;
};

}  // namespace mr::surface_union
