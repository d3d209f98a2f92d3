#include "union_checks.h"

#include "union/surface_union.h"

#include <map>

namespace mr::test {

using surface_union::Body;
using surface_union::Result;

Watertight watertight(const Result& r) {
  std::map<std::pair<int, int>, std::array<int, 2>> edges;
  for (const auto& f : r.faces)
    for (int z = 0; z < 3; ++z) {
      const int u = f[z], v = f[(z + 1) % 3];
      ++edges[{std::min(u, v), std::max(u, v)}][u < v ? 0 : 1];
    }
  Watertight w;
  for (const auto& [e, c] : edges) {
    if (c[0] + c[1] == 1) ++w.boundary_edges;
    else if (c[0] + c[1] > 2) ++w.nonmanifold_edges;
    else if (c[0] != 1) ++w.misoriented_edges;
  }
  return w;
}

static double tet(const std::array<double, 3>& p, const std::array<double, 3>& q, const std::array<double, 3>& r) {
  return (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) + p[2] * (q[0] * r[1] - q[1] * r[0])) / 6;
}

double volume(const Result& r) {
  double v = 0;
  for (const auto& f : r.faces) v += tet(r.vertices[f[0]], r.vertices[f[1]], r.vertices[f[2]]);
  return v;
}

double volume(const Body& b) {
  double v = 0;
  for (const auto& f : b.faces) v += tet(b.vertices[f[0]], b.vertices[f[1]], b.vertices[f[2]]);
  return v;
}

Body make_body(const TriMesh& m, double dx, double dy, double dz, double scale) {
  Body b = surface_union::body_from_mesh(m, "");
  for (auto& p : b.vertices) {
    p[0] = p[0] * scale + dx;
    p[1] = p[1] * scale + dy;
    p[2] = p[2] * scale + dz;
  }
  return b;
}

}  // namespace mr::test
