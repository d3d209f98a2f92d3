#include "union/self_intersection.h"

#include "common/union_find.h"
#include "union/exact.h"
#include "union/face_clearance.h"
#include "union/triangle_angles.h"

#include <algorithm>
#include <vector>

namespace mr::surface_union {

namespace {

/// Where the surface is locally convex. A vertex is when every edge at it is convex or
/// flat (exact) and its face angles sum to at most 2 pi (doubles: within 1e-9 counts as
/// flat): two faces at such a vertex lie on a convex cone there and meet only at it or
/// along an edge. A body that is one piece and convex at every vertex bounds a convex
/// body (a closed, locally convex surface: Van Heijenoort 1952) and cannot cross itself.
struct Convexity {
  std::vector<char> vertex;  // per vertex
  bool whole = false;
};

Convexity convexity(const Body& b, const EdgeTable& edges, bool outward) {
  const int nf = int(b.faces.size());
  Convexity out;
  out.vertex.assign(b.vertices.size(), 1);
  // A convex edge has its neighbour's third corner below the face's plane, seen from outside.
  const int reflex = outward ? 1 : -1;
  UnionFind pieces(nf);
  for (int e = 0; e < edges.edge_count(); ++e) {
    if (edges.valence(e) != 2) {  // not closed and manifold: no vertex is known to be convex
      out.vertex.assign(b.vertices.size(), 0);
      return out;
    }
    const FaceSide s = edges.side(e, 0), o = edges.side(e, 1);
    pieces.unite(s.face, o.face);
    const auto& t = b.faces[size_t(s.face)];
    const int d = b.faces[size_t(o.face)][size_t((o.side + 2) % 3)];
    if (orient3d(b.vertices[size_t(t[size_t(s.side)])].data(), b.vertices[size_t(t[size_t((s.side + 1) % 3)])].data(),
                 b.vertices[size_t(t[size_t((s.side + 2) % 3)])].data(), b.vertices[size_t(d)].data()) == reflex)
      out.vertex[size_t(edges.v0(e))] = out.vertex[size_t(edges.v1(e))] = 0;
  }
  std::vector<double> angle(b.vertices.size(), 0);
  for (const auto& t : b.faces)
    for (int z = 0; z < 3; ++z)
      if (out.vertex[size_t(t[size_t(z)])])  // (reflex already: its angles do not matter)
        angle[size_t(t[size_t(z)])] += corner_angle(b.vertices[size_t(t[size_t(z)])],
                                                    b.vertices[size_t(t[size_t((z + 1) % 3)])],
                                                    b.vertices[size_t(t[size_t((z + 2) % 3)])]);
  for (size_t v = 0; v < angle.size(); ++v)
    if (angle[v] > 2 * 3.14159265358979323846 + 1e-9) out.vertex[v] = 0;
  out.whole = std::all_of(out.vertex.begin(), out.vertex.end(), [](char c) { return c != 0; });
  for (int f = 1; f < nf && out.whole; ++f) out.whole = pieces.find(f) == pieces.find(0);
  return out;
}

}  // namespace

bool faces_outward(const Body& b) {
  double vol = 0;
  for (const auto& f : b.faces) {
    const auto &p = b.vertices[size_t(f[0])], &q = b.vertices[size_t(f[1])], &r = b.vertices[size_t(f[2])];
    vol += p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) + p[2] * (q[0] * r[1] - q[1] * r[0]);
  }
  return vol >= 0;
}

std::optional<std::array<int, 2>> self_intersection(const Body& b) {
  return self_intersection(b, EdgeTable(b.vertices.size(), b.faces), faces_outward(b));
}

std::optional<std::array<int, 2>> self_intersection(const Body& b, const EdgeTable& edges, bool outward) {
  const int nf = int(b.faces.size());
  if (nf < 2) return std::nullopt;
  const Convexity convex = convexity(b, edges, outward);
  if (convex.whole) return std::nullopt;
  FaceGrid grid(b.vertices, b.faces);
  std::vector<int> near;
  for (int f = 0; f < nf; ++f) {
    V3 lo, hi;
    grid.box(f, lo, hi);
    grid.near(lo, hi, near);
    const auto& tf = b.faces[size_t(f)];
    for (int g : near) {
      if (g <= f) continue;  // each pair once
      const auto& tg = b.faces[size_t(g)];
      int shared = 0, at = -1;
      for (int x : tf)
        if (x == tg[0] || x == tg[1] || x == tg[2]) { ++shared; at = x; }
      if (shared >= 2) continue;                              // neighbours across an edge meet only along it
      if (shared == 1 && convex.vertex[size_t(at)]) continue;  // on a convex cone at their corner
      const V3 pf[3] = {b.vertices[size_t(tf[0])], b.vertices[size_t(tf[1])], b.vertices[size_t(tf[2])]};
      const V3 pg[3] = {b.vertices[size_t(tg[0])], b.vertices[size_t(tg[1])], b.vertices[size_t(tg[2])]};
      if (triangles_meet(tf, pf, tg, pg)) return std::array<int, 2>{f, g};
    }
  }
  return std::nullopt;
}

}  // namespace mr::surface_union
