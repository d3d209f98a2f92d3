#include "union/link_triangulation.h"

#include "union/triangle_angles.h"
#include "union/vec3.h"

#include <algorithm>
#include <cmath>

namespace mr::surface_union {

namespace {

// Diagonals (i, j) and (a, b) of one polygon cross when exactly one of a, b lies strictly
// between i and j.
bool diagonals_cross(int i, int j, int a, int b) {
  if (i == a || i == b || j == a || j == b) return false;
  const bool a_in = i < a && a < j, b_in = i < b && b < j;
  return a_in != b_in;
}

}  // namespace

bool best_polygon_triangulation(const std::vector<V3>& ring, const V3& up, const std::function<bool(int, int)>& allowed,
                                std::array<int, 2> forced, std::vector<std::array<int, 3>>& out, double& min_angle,
                                double must_exceed) {
  const int k = int(ring.size());
  out.clear();
  if (k < 3) return false;
  if (forced[0] > forced[1]) std::swap(forced[0], forced[1]);
  const bool has_forced = forced[0] >= 0;
  auto side = [&](int i, int j) { return j == i + 1 || (i == 0 && j == k - 1); };
  auto usable = [&](int i, int j) {
    if (side(i, j)) return true;
    if (has_forced && i == forced[0] && j == forced[1]) return true;
    if (has_forced && diagonals_cross(i, j, forced[0], forced[1])) return false;
    return allowed(i, j);
  };
  std::vector<char> ok(size_t(k) * k, 0);  // usable(i, j), asked once per pair
  for (int i = 0; i < k; ++i)
    for (int j = i + 1; j < k; ++j) ok[size_t(i) * k + j] = usable(i, j);
  // best[i][j]: the best smallest angle of the sub-polygon i..j (closed by (i, j)).
  constexpr double kNone = -1;
  std::vector<double> best(size_t(k) * k, kNone);
  std::vector<int> apex(size_t(k) * k, -1);
  auto at = [k](int i, int j) { return size_t(i) * k + j; };
  for (int i = 0; i + 1 < k; ++i) best[at(i, i + 1)] = 1e300;
  for (int len = 2; len < k; ++len)
    for (int i = 0; i + len < k; ++i) {
      const int j = i + len;
      if (!ok[at(i, j)]) continue;
      for (int m = i + 1; m < j; ++m) {
        const double left = best[at(i, m)], right = best[at(m, j)];
        // The triangle's angle is only needed when it could improve on the best so far
        // and on the bound (branch and bound: the same result, fewer atan2).
        const double sides = std::min(left, right);
        if (left < 0 || right < 0 || sides <= best[at(i, j)] || sides <= must_exceed) continue;
        const V3 n = cross(sub3(ring[m], ring[i]), sub3(ring[j], ring[i]));
        if (!(dot(n, up) > 0)) continue;
        const double q = std::min(smallest_angle(ring[i], ring[m], ring[j]), sides);
        if (q > best[at(i, j)] && q > must_exceed) {
          best[at(i, j)] = q;
          apex[at(i, j)] = m;
        }
      }
    }
  if (best[at(0, k - 1)] < 0 || !(best[at(0, k - 1)] > must_exceed)) return false;
  min_angle = best[at(0, k - 1)];
  std::vector<std::array<int, 2>> todo{{0, k - 1}};
  while (!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    if (j <= i + 1) continue;
    const int m = apex[at(i, j)];
    out.push_back({i, m, j});
    todo.push_back({i, m});
    todo.push_back({m, j});
  }
  return true;
}

}  // namespace mr::surface_union
