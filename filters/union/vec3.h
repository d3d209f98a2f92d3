// The union's 3D points and the few vector operations its steps share.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace mr::surface_union {

using V3 = std::array<double, 3>;

inline V3 sub3(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const V3& a) { return std::sqrt(dot(a, a)); }

/// Hash of a position's exact coordinates (-0 and +0 hash alike, as they compare equal),
/// for hash tables keyed by points.
inline size_t hash_position(double x, double y, double z) {
  uint64_t h = 1469598103934665603ull;
  for (double v : {x, y, z}) {
    if (v == 0) v = 0;
    uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    h = (h ^ bits) * 1099511628211ull;
    h ^= h >> 29;
  }
  return size_t(h);
}

}  // namespace mr::surface_union
