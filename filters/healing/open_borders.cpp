#include "healing/open_borders.h"

#include "common/uniform_grid.h"
#include "healing/segment_geometry.h"

#include <algorithm>
#include <cmath>

namespace mr::healing {
OpenBorders find_open_borders(const Soup& s, const SoupEdges& edges, double radius) {
  OpenBorders out;
  out.side_open.assign(s.tri.size(), {false, false, false});
  std::vector<int> open;
  UnionFind loops(int(s.pos.size()));
  std::vector<char> on_border(s.pos.size(), 0);
  for (size_t e = 0; e < edges.size(); ++e) {
    if (edges[e].sides.size() != 1) continue;
    open.push_back(int(e));
    out.side_open[edges[e].sides[0][0]][edges[e].sides[0][1]] = true;
    loops.unite(edges[e].v0, edges[e].v1);
    on_border[edges[e].v0] = on_border[edges[e].v1] = 1;
  }
  out.edges = int(open.size());
  for (int v = 0; v < int(s.pos.size()); ++v)
    if (on_border[v] && loops.find(v) == v) ++out.loops;
  if (open.empty() || !(radius > 0)) return out;

  UniformGrid grid(radius);
  for (size_t i = 0; i < open.size(); ++i) {
    grid.insert_segment(int(i), s.pos[edges[open[i]].v0], s.pos[edges[open[i]].v1], 0);
  }
  for (size_t i = 0; i < open.size(); ++i) {
    const SoupEdge& e = edges[open[i]];
    const Point3 mid = (s.pos[e.v0] + s.pos[e.v1]) * 0.5;
    Point3 dir = s.pos[e.v1] - s.pos[e.v0];
    dir.Normalize();
    double nearest = radius;
    bool found = false;
    grid.visit(mid, radius, [&](int j) {
      const SoupEdge& g = edges[open[j]];
      if (g.v0 == e.v0 || g.v0 == e.v1 || g.v1 == e.v0 || g.v1 == e.v1) return;
      Point3 gdir = s.pos[g.v1] - s.pos[g.v0];
      gdir.Normalize();
      if (std::abs(dir * gdir) < 0.5) return;  // a border running across, not alongside
      const double d = point_segment_distance(mid, s.pos[g.v0], s.pos[g.v1]);
      if (d <= nearest) { nearest = d; found = true; }
    });
    if (found) { ++out.gaps; out.largest_gap = std::max(out.largest_gap, nearest); }
  }
  return out;
}

}  // namespace mr::healing
