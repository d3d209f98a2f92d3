#include "union/sliver_collapse.h"

#include <algorithm>
#include <cmath>

namespace mr::surface_union {

double min_angle_deg(const std::vector<std::array<double, 3>>& v, const std::vector<std::array<int, 3>>& f) {
  double best = 180;
  for (const auto& t : f)
    for (int z = 0; z < 3; ++z) {
      const auto &o = v[t[z]], &p = v[t[(z + 1) % 3]], &q = v[t[(z + 2) % 3]];
      double a[3], b[3];
      for (int k = 0; k < 3; ++k) { a[k] = p[k] - o[k]; b[k] = q[k] - o[k]; }
      const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
      const double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2], cz = a[0] * b[1] - a[1] * b[0];
      best = std::min(best, std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dot) * 180 / 3.14159265358979323846);
    }
  return best;
}

int collapse_slivers(Result&, double, double) { return 0; }

}  // namespace mr::surface_union
