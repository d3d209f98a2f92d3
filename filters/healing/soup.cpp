#include "healing/soup.h"

#include <algorithm>
#include <cstdint>

namespace mr::healing {

SoupEdges soup_edges(const Soup& s) {
  // Bucket the half-edges on their lower vertex (counting sort, O(N)), then
  // order each small bucket by upper vertex: the same order a full sort gives.
  const size_t nv = s.pos.size();
  std::vector<int> begin(nv + 1, 0);
  for (const auto& t : s.tri)
    for (int z = 0; z < 3; ++z)
      if (t[z] != t[(z + 1) % 3]) ++begin[std::min(t[z], t[(z + 1) % 3]) + 1];
  for (size_t v = 0; v < nv; ++v) begin[v + 1] += begin[v];
  std::vector<std::pair<int, int>> half(begin[nv]);  // (upper vertex, face*3+side)
  std::vector<int> fill(begin.begin(), begin.end() - 1);
  for (size_t f = 0; f < s.tri.size(); ++f)
    for (int z = 0; z < 3; ++z) {
      const int a = s.tri[f][z], b = s.tri[f][(z + 1) % 3];
      if (a == b) continue;
      half[fill[std::min(a, b)]++] = {std::max(a, b), int(f) * 3 + z};
    }
  SoupEdges out;
  out.sides_.reserve(half.size());
  for (size_t v = 0; v < nv; ++v) {
    std::sort(half.begin() + begin[v], half.begin() + begin[v + 1]);
    for (int i = begin[v]; i < begin[v + 1];) {
      int j = i;
      while (j < begin[v + 1] && half[j].first == half[i].first) ++j;
      SoupEdge e;
      e.v0 = int(v);
      e.v1 = half[i].first;
      e.sides = {nullptr, j - i};
      for (int k = i; k < j; ++k) out.sides_.push_back({half[k].second / 3, half[k].second % 3});
      out.edges_.push_back(e);
      i = j;
    }
  }
  // The side array is complete: point the spans into it.
  size_t offset = 0;
  for (auto& e : out.edges_) { e.sides.first = out.sides_.data() + offset; offset += e.sides.count; }
  return out;
}

}  // namespace mr::healing
