#include "remesh/flat_pockets.h"

#include <map>

namespace mr::remesh {

int remove_flat_pockets(OutputMesh& out) {
  // Faces by their sorted points; a pair with opposite orientations goes. (Two with the same
  // orientation would overlap, which the front's crossing checks prevent.)
  std::map<std::array<int, 3>, std::vector<int>> by_points;
  for (int f = 0; f < int(out.faces.size()); ++f) {
    const auto& t = out.faces[size_t(f)];
    by_points[OutputMesh::triangle_key(t[0], t[1], t[2])].push_back(f);
  }
  auto reversed = [&](int f, int g) {
    const auto& a = out.faces[size_t(f)];
    const auto& b = out.faces[size_t(g)];
    for (int z = 0; z < 3; ++z)
      if (a[0] == b[size_t(z)]) return a[1] == b[size_t((z + 2) % 3)];
    return false;
  };
  std::vector<char> gone(out.faces.size(), 0);
  int pairs = 0;
  for (const auto& [key, faces] : by_points) {
    if (faces.size() != 2 || !reversed(faces[0], faces[1])) continue;
    gone[size_t(faces[0])] = gone[size_t(faces[1])] = 1;
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
