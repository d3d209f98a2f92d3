#include "remesh/strip_staggering.h"

#include <algorithm>
#include <cmath>

namespace mr::remesh {

std::vector<double> staggered_positions(const std::vector<Point3>& polyline, const std::vector<double>& cumulative,
                                        const std::vector<Point3>& opposite_points, double reach) {
  const double total = cumulative.back();
  std::vector<double> at;
  for (const Point3& m : opposite_points) {
    double best = reach, best_at = -1;
    for (size_t j = 0; j + 1 < polyline.size(); ++j) {
      const Point3 d = polyline[j + 1] - polyline[j];
      const double len2 = d.SquaredNorm();
      const double u = len2 > 0 ? std::clamp(((m - polyline[j]) * d) / len2, 0.0, 1.0) : 0.0;
      const double dist = (polyline[j] + d * u - m).Norm();
      if (dist <= best) { best = dist; best_at = cumulative[j] + u * (cumulative[j + 1] - cumulative[j]); }
    }
    if (best_at > 0 && best_at < total) at.push_back(best_at);
  }
  if (at.empty()) return {};
  std::sort(at.begin(), at.end());
  at.push_back(total);
  // Points closer than a quarter element to the one kept before them are dropped.
  std::vector<double> out{0.0};
  auto keep = [&](double x) { if (x - out.back() >= 0.25) out.push_back(x); };
  double previous = 0.0;
  for (double x : at) {
    const double gap = x - previous;
    const long extra = std::max(std::lround(gap) - 1, 0L);
    for (long e = 1; e <= extra; ++e) keep(previous + gap * double(e) / double(extra + 1));
    if (x < total) keep(x);
    previous = x;
  }
  if (out.size() > 1 && total - out.back() < 0.25) out.pop_back();
  out.push_back(total);
  return out;
}

}  // namespace mr::remesh
