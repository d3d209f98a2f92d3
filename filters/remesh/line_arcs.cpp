#include "remesh/line_arcs.h"

#include <algorithm>

namespace mr::remesh {

std::vector<double> cumulative_arc(const LinePath& path) {
  std::vector<double> c(path.polyline.size(), 0.0);
  for (size_t j = 1; j < path.polyline.size(); ++j) c[j] = c[j - 1] + (path.polyline[j] - path.polyline[j - 1]).Norm();
  return c;
}

ArcPlacement at_arc(const LinePath& path, const std::vector<double>& cumulative, double s) {
  const size_t segs = path.polyline.size() - 1;
  size_t seg = std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin();
  seg = std::clamp<size_t>(seg, 1, segs) - 1;
  const double len = cumulative[seg + 1] - cumulative[seg];
  const double u = len > 0 ? std::clamp((s - cumulative[seg]) / len, 0.0, 1.0) : 0.0;
  return {path.polyline[seg] * (1 - u) + path.polyline[seg + 1] * u, int(seg)};
}

std::vector<std::array<int, 2>> slidable_slots(const std::vector<LinePath>& paths, size_t nv) {
  std::vector<std::array<int, 2>> slot(nv, {-1, -1});
  for (size_t p = 0; p < paths.size(); ++p) {
    if (paths[p].polyline.size() < 2) continue;
    for (size_t i = 1; i + 1 < paths[p].points.size(); ++i)
      if (paths[p].slidable[i]) slot[size_t(paths[p].points[i])] = {int(p), int(i)};
  }
  return slot;
}

}  // namespace mr::remesh
