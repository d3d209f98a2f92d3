#include "healing/open_borders.h"

#include "common/uniform_grid.h"
#include "healing/border_grid.h"
#include "common/segment_geometry.h"

#include <algorithm>
#include <cmath>

namespace mr::healing {
OpenBorders find_open_borders(const Soup& s, const EdgeTable& edges, double radius) {
  OpenBorders out;
  out.side_open.assign(s.tri.size(), {false, false, false});
  std::vector<int> open;
  UnionFind loops(int(s.pos.size()));
  std::vector<char> on_border(s.pos.size(), 0);
  for (int e = 0; e < edges.edge_count(); ++e) {
    if (edges.valence(e) != 1) continue;
    open.push_back(int(e));
    out.side_open[edges.side(e, 0).face][edges.side(e, 0).side] = true;
    loops.unite(edges.v0(e), edges.v1(e));
    on_border[edges.v0(e)] = on_border[edges.v1(e)] = 1;
  }
  out.edges = int(open.size());
  for (int v = 0; v < int(s.pos.size()); ++v)
    if (on_border[v] && loops.find(v) == v) ++out.loops;
  if (open.empty() || !(radius > 0)) return out;

  UniformGrid grid(border_grid_cell(s, edges, open, radius));
  for (size_t i = 0; i < open.size(); ++i) {
    grid.insert_segment(int(i), s.pos[edges.v0(open[i])], s.pos[edges.v1(open[i])], 0);
  }
  for (size_t i = 0; i < open.size(); ++i) {
    const auto e = edges.ends(open[i]);
    const Point3 mid = (s.pos[e.v0] + s.pos[e.v1]) * 0.5;
    Point3 dir = s.pos[e.v1] - s.pos[e.v0];
    dir.Normalize();
    double nearest = radius;
    bool found = false;
    grid.visit(mid, radius, [&](int j) {
      const auto g = edges.ends(open[j]);
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
