// The one table of exact points of a union run: input vertices and every
// constructed intersection point. A point is stored once, whatever computed it,
// because equal rationals are equal: neighbouring faces share vertices exactly.
#pragma once

#include "common/flat_index_map.h"
#include "union/exact.h"

#include <array>
#include <vector>

namespace mr::surface_union {

class PointTable {
public:
  /// Index of `p`, adding it if no equal point is stored yet.
  int insert(QPoint&& p);
  /// The same for a point known to lie on the line through points u and w (an edge
  /// crossing): predicates can then tell that it is collinear with them for free.
  int insert_on_line(QPoint&& p, int u, int w);
  /// Records that point id lies on the line through points u and w (up to two lines
  /// are kept: a crossing of two segments lies on both).
  void mark_on_line(int id, int u, int w);
  /// Points a, b, c are known to be collinear (one was built on the line of the others).
  bool known_collinear(int a, int b, int c) const;
  const QPoint& operator[](int i) const { return points_[i]; }
  int size() const { return int(points_.size()); }
  void reserve(size_t n) {
    points_.reserve(n);
    next_.reserve(n);
    line_.reserve(n);
    index_.reserve(n);
  }

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
  // distinct points with one key are told apart exactly. The map holds the first
  // point of a key, next_ chains the others (no allocation per key).
  FlatIndexMap<Key, KeyHash> index_;
  std::vector<int> next_;
  using Line = std::array<int, 2>;           // (u, w) with u < w, or (-1, -1)
  std::vector<std::array<Line, 2>> line_;  // per point: lines it is known to lie on
};

}  // namespace mr::surface_union
