#include "healing/orientation.h"

#include <queue>

namespace mr::healing {

Orientation orient_consistently(Soup& s, bool outward) {
  Orientation out;
  const auto edges = soup_edges(s);
  const int nf = int(s.tri.size());
  // For every face side: the edge it lies on.
  std::vector<int> side_edge(3 * nf, -1);
  for (size_t e = 0; e < edges.size(); ++e)
    for (const auto& fs : edges[e].sides) side_edge[3 * fs[0] + fs[1]] = int(e);

  std::vector<int> flip(nf, -1);
  for (int seed = 0; seed < nf; ++seed) {
    if (flip[seed] >= 0) continue;
    std::vector<int> component = {seed};
    bool closed = true;
    flip[seed] = 0;
    std::queue<int> queue;
    queue.push(seed);
    while (!queue.empty()) {
      const int f = queue.front();
      queue.pop();
      for (int z = 0; z < 3; ++z) {
        const int e = side_edge[3 * f + z];
        if (e < 0) continue;
        if (edges[e].sides.size() != 2) { closed = false; continue; }
        const auto other = edges[e].sides[0][0] == f && edges[e].sides[0][1] == z ? edges[e].sides[1]
                                                                                     : edges[e].sides[0];
        const int g = other[0];
        const bool same_direction = s.tri[f][z] == s.tri[g][other[1]];
        const int want = flip[f] ^ int(same_direction);
        if (flip[g] < 0) {
          flip[g] = want;
          component.push_back(g);
          queue.push(g);
        } else if (flip[g] != want && f < g) {
          ++out.conflicts;
        }
      }
    }
    int flipped = 0;
    for (int f : component) flipped += flip[f];
    bool invert;
    if (closed && outward) {
      double volume = 0;  // six times the signed volume, with the flips applied
      for (int f : component) {
        const auto& t = s.tri[f];
        const double v = s.pos[t[0]] * (s.pos[t[1]] ^ s.pos[t[2]]);
        volume += flip[f] ? -v : v;
      }
      invert = volume < 0;
    } else {
      invert = 2 * flipped > int(component.size());
    }
    if (invert)
      for (int f : component) flip[f] ^= 1;
  }
  for (int f = 0; f < nf; ++f)
    if (flip[f]) { std::swap(s.tri[f][1], s.tri[f][2]); ++out.faces_flipped; }
  return out;
}

}  // namespace mr::healing
