#include "remesh/flat_pockets.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace mr::remesh {

int remove_flat_pockets(OutputMesh& out) {
  // Faces sorted by their sorted points (no allocation per face: outputs run to millions);
  // a run of exactly two with opposite orientations goes. (Two with the same orientation
  // would overlap, which the front's crossing checks prevent.)
  std::vector<std::pair<std::array<int, 3>, int>> by_points(out.faces.size());
  for (size_t f = 0; f < out.faces.size(); ++f) {
    const auto& t = out.faces[f];
    by_points[f] = {OutputMesh::triangle_key(t[0], t[1], t[2]), int(f)};
  }
  std::sort(by_points.begin(), by_points.end());
  auto reversed = [&](int f, int g) {
    const auto& a = out.faces[size_t(f)];
    const auto& b = out.faces[size_t(g)];
    for (int z = 0; z < 3; ++z)
      if (a[0] == b[size_t(z)]) return a[1] == b[size_t((z + 2) % 3)];
    return false;
  };
  std::vector<char> gone(out.faces.size(), 0);
  int pairs = 0;
  for (size_t i = 0, j; i < by_points.size(); i = j) {
    for (j = i + 1; j < by_points.size() && by_points[j].first == by_points[i].first;) ++j;
    if (j - i != 2 || !reversed(by_points[i].second, by_points[i + 1].second)) continue;
    gone[size_t(by_points[i].second)] = gone[size_t(by_points[i + 1].second)] = 1;
    ++pairs;
  }
  if (pairs == 0) return 0;
  size_t k = 0;
  for (size_t f = 0; f < out.faces.size(); ++f) {
    if (gone[f]) continue;
    out.faces[k] = out.faces[f];
    out.face_patch[k] = out.face_patch[f];
    ++k;
  }
  out.faces.resize(k);
  out.face_patch.resize(k);
  out.rebuild_shared_edges();
  return pairs;
}

}  // namespace mr::remesh
