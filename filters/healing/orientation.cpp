#include "healing/orientation.h"

#include <queue>

namespace mr::healing {

Orientation orient_consistently(Soup& s, bool outward) {
  Orientation out;
  const auto edges = soup_edges(s);
  const int nf = int(s.tri.size());

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
        const int e = edges.edge_of(f, z);
        if (e < 0) continue;
        if (edges.valence(e) != 2) { closed = false; continue; }
        const FaceSide other = edges.side(e, 0).face == f && edges.side(e, 0).side == z ? edges.side(e, 1)
                                                                                         : edges.side(e, 0);
        const int g = other.face;
        const bool same_direction = s.tri[f][z] == s.tri[g][other.side];
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
      // Six times the signed volume, with the flips applied, about a vertex of the part
      // (about the origin, a part far from it cancels to noise).
      double volume = 0;
      const auto o = s.pos[s.tri[component[0]][0]];
      for (int f : component) {
        const auto& t = s.tri[f];
        const double v = (s.pos[t[0]] - o) * ((s.pos[t[1]] - o) ^ (s.pos[t[2]] - o));
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
