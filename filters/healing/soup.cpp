#include "healing/soup.h"

#include <algorithm>
#include <cstdint>

namespace mr::healing {

std::vector<SoupEdge> soup_edges(const Soup& s) {
  std::vector<std::pair<uint64_t, int>> half;  // (edge key, face*3+side)
  half.reserve(s.tri.size() * 3);
  for (size_t f = 0; f < s.tri.size(); ++f)
    for (int z = 0; z < 3; ++z) {
      const int a = s.tri[f][z], b = s.tri[f][(z + 1) % 3];
      if (a == b) continue;
      const uint64_t key = (uint64_t(std::min(a, b)) << 32) | uint32_t(std::max(a, b));
      half.push_back({key, int(f) * 3 + z});
    }
  std::sort(half.begin(), half.end());
  std::vector<SoupEdge> edges;
  for (size_t i = 0; i < half.size();) {
    SoupEdge e;
    e.v0 = int(half[i].first >> 32);
    e.v1 = int(half[i].first & 0xffffffffu);
    size_t j = i;
    for (; j < half.size() && half[j].first == half[i].first; ++j)
      e.sides.push_back({half[j].second / 3, half[j].second % 3});
    edges.push_back(std::move(e));
    i = j;
  }
  return edges;
}

std::vector<std::vector<int>> vertex_neighbours(const Soup& s) {
  std::vector<std::vector<int>> nb(s.pos.size());
  for (const auto& t : s.tri)
    for (int z = 0; z < 3; ++z) {
      const int a = t[z], b = t[(z + 1) % 3];
      if (a == b) continue;
      nb[a].push_back(b);
      nb[b].push_back(a);
    }
  for (auto& n : nb) {
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
  }
  return nb;
}

}  // namespace mr::healing
