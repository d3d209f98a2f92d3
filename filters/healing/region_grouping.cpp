#include "healing/region_grouping.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace mr::healing {

Regions group_patches(const Soup& s, const EdgeTable& edges, const std::vector<std::array<int, 2>>& welded, double angle_deg) {
  Regions out;
  const int nf = int(s.tri.size());
  out.feature.assign(nf, {false, false, false});
  auto key = [](int a, int b) { return (uint64_t(std::min(a, b)) << 32) | uint32_t(std::max(a, b)); };
  std::vector<uint64_t> welded_keys;
  for (const auto& w : welded) welded_keys.push_back(key(w[0], w[1]));
  std::sort(welded_keys.begin(), welded_keys.end());

  std::vector<Point3> normal(nf);
  for (int f = 0; f < nf; ++f) {
    const auto& t = s.tri[f];
    normal[f] = (s.pos[t[1]] - s.pos[t[0]]) ^ (s.pos[t[2]] - s.pos[t[0]]);
    normal[f].Normalize();
  }
  const double cos_limit = std::cos(angle_deg * M_PI / 180.0);
  UnionFind groups(nf);
  for (int e = 0; e < edges.edge_count(); ++e) {
    if (edges.valence(e) != 2) continue;
    const FaceSide a = edges.side(e, 0), b = edges.side(e, 1);
    const int f = a.face, g = b.face;
    const bool seam = s.patch[f] != s.patch[g] ||
                      std::binary_search(welded_keys.begin(), welded_keys.end(), key(edges.v0(e), edges.v1(e)));
    if (seam && normal[f] * normal[g] < cos_limit) {
      out.feature[f][a.side] = out.feature[g][b.side] = true;
      ++out.feature_edges;
    } else {
      groups.unite(f, g);
    }
  }
  out.group.assign(nf, -1);
  std::vector<int> id_of_root(nf, -1);
  for (int f = 0; f < nf; ++f) {
    int& id = id_of_root[groups.find(f)];
    if (id < 0) id = out.groups++;
    out.group[f] = id;
  }
  return out;
}

}  // namespace mr::healing
