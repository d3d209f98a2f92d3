#include "union/self_intersection.h"

#include "common/union_find.h"
#include "union/exact.h"
#include "union/face_clearance.h"
#include "union/triangle_angles.h"
#include "union/vec3.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mr::surface_union {

namespace {

/// Where the surface is locally convex (per vertex). A vertex is when every edge at it is
/// convex or flat (exact) and its face angles sum to at most 2 pi (doubles: within 1e-9
/// counts as flat): two faces at such a vertex lie on a convex cone there and meet only at
/// it or along an edge. (A body convex at every vertex is also star-shaped, below.)
std::vector<char> convex_vertices(const Body& b, const EdgeTable& edges, bool outward) {
  std::vector<char> convex(b.vertices.size(), 1);
  // A convex edge has its neighbour's third corner below the face's plane, seen from outside.
  const int reflex = outward ? 1 : -1;
  for (int e = 0; e < edges.edge_count(); ++e) {
    if (edges.valence(e) != 2) {  // not closed and manifold: no vertex is known to be convex
      convex.assign(b.vertices.size(), 0);
      return convex;
    }
    const FaceSide s = edges.side(e, 0), o = edges.side(e, 1);
    const auto& t = b.faces[size_t(s.face)];
    const int d = b.faces[size_t(o.face)][size_t((o.side + 2) % 3)];
    if (orient3d(b.vertices[size_t(t[size_t(s.side)])].data(), b.vertices[size_t(t[size_t((s.side + 1) % 3)])].data(),
                 b.vertices[size_t(t[size_t((s.side + 2) % 3)])].data(), b.vertices[size_t(d)].data()) == reflex)
      convex[size_t(edges.v0(e))] = convex[size_t(edges.v1(e))] = 0;
  }
  std::vector<double> angle(b.vertices.size(), 0);
  for (const auto& t : b.faces)
    for (int z = 0; z < 3; ++z)
      if (convex[size_t(t[size_t(z)])])  // (reflex already: its angles do not matter)
        angle[size_t(t[size_t(z)])] += corner_angle(b.vertices[size_t(t[size_t(z)])],
                                                    b.vertices[size_t(t[size_t((z + 1) % 3)])],
                                                    b.vertices[size_t(t[size_t((z + 2) % 3)])]);
  for (size_t v = 0; v < angle.size(); ++v)
    if (angle[v] > 2 * 3.14159265358979323846 + 1e-9) convex[v] = 0;
  return convex;
}

/// Vertices whose star is one to one in a projection on a coordinate plane (per vertex: the
/// plane across the largest component of its faces' summed normal): every face at v turns
/// the same way there, strictly (exact), and their angles at v add up to one turn (doubles:
/// under 3 pi; a fan closing twice, or two fans at one vertex, make at least 4 pi). The
/// faces then lie in consecutive sectors around v's image without overlap, so two of them
/// that share only v meet only at v. Smooth surfaces (scans, organic bodies) have this at
/// nearly every vertex, convex or not. Needs a closed, manifold body (every fan closed).
std::vector<char> vertices_with_flat_stars(const Body& b, const EdgeTable& edges) {
  std::vector<char> flat(b.vertices.size(), 0);
  for (int e = 0; e < edges.edge_count(); ++e)
    if (edges.valence(e) != 2) return flat;
  std::vector<V3> normal(b.vertices.size(), V3{0, 0, 0});
  for (const auto& t : b.faces) {
    const V3 n = cross(sub3(b.vertices[size_t(t[1])], b.vertices[size_t(t[0])]),
                       sub3(b.vertices[size_t(t[2])], b.vertices[size_t(t[0])]));
    for (int v : t)
      for (size_t k = 0; k < 3; ++k) normal[size_t(v)][k] += n[k];
  }
  std::vector<int> axis(b.vertices.size()), sign(b.vertices.size());
  for (size_t v = 0; v < b.vertices.size(); ++v) {
    const V3& n = normal[v];
    axis[v] = std::fabs(n[0]) >= std::fabs(n[1]) && std::fabs(n[0]) >= std::fabs(n[2]) ? 0
              : std::fabs(n[1]) >= std::fabs(n[2])                                  ? 1
                                                                                    : 2;
    sign[v] = n[size_t(axis[v])] > 0 ? 1 : n[size_t(axis[v])] < 0 ? -1 : 0;
    flat[v] = sign[v] != 0;
  }
  std::vector<double> turn(b.vertices.size(), 0);
  for (const auto& t : b.faces)
    for (size_t z = 0; z < 3; ++z) {
      const size_t v = size_t(t[z]);
      if (!flat[v]) continue;
      const int i = (axis[v] + 1) % 3, j = (axis[v] + 2) % 3;
      const V3 &p = b.vertices[v], &a = b.vertices[size_t(t[(z + 1) % 3])], &c = b.vertices[size_t(t[(z + 2) % 3])];
      if (orient2d(p.data(), a.data(), c.data(), i, j) != sign[v]) {
        flat[v] = 0;
        continue;
      }
      const double ux = a[size_t(i)] - p[size_t(i)], uy = a[size_t(j)] - p[size_t(j)];
      const double wx = c[size_t(i)] - p[size_t(i)], wy = c[size_t(j)] - p[size_t(j)];
      turn[v] += std::atan2(std::fabs(ux * wy - uy * wx), ux * wx + uy * wy);
    }
  for (size_t v = 0; v < turn.size(); ++v)
    if (!(turn[v] < 3 * 3.14159265358979323846)) flat[v] = 0;
  return flat;
}

/// Whether b is star-shaped about its vertex centroid c in the sense that proves it
/// embedded: closed, manifold along edges, one piece, every face strictly facing away from
/// c (exact), and the faces at each vertex going once around it as seen from c. The
/// projection from c onto a sphere is then a local homeomorphism of a connected closed
/// surface onto the sphere: a covering, one sheet as the sphere is simply connected, so
/// no two points of the surface share a ray from c and no faces cross. Convex bodies and
/// blobs (molecules, the rabbit's parts, noisy spheres) pass; CAD plates with holes do not.
bool star_shaped(const Body& b, const EdgeTable& edges, bool outward) {
  const int nf = int(b.faces.size());
  UnionFind pieces(nf);
  for (int e = 0; e < edges.edge_count(); ++e) {
    if (edges.valence(e) != 2) return false;
    pieces.unite(edges.side(e, 0).face, edges.side(e, 1).face);
  }
  for (int f = 1; f < nf; ++f)
    if (pieces.find(f) != pieces.find(0)) return false;
  V3 c{0, 0, 0};  // (each term divided first: no overflow near the largest doubles)
  const double count = double(b.vertices.size());
  for (const V3& p : b.vertices)
    for (size_t k = 0; k < 3; ++k) c[k] += p[k] / count;
  const int inner = outward ? -1 : 1;  // orient3d's sign for a point on a face's inner side
  std::vector<double> turn(b.vertices.size(), 0);
  for (const auto& t : b.faces) {
    const V3 &p = b.vertices[size_t(t[0])], &q = b.vertices[size_t(t[1])], &r = b.vertices[size_t(t[2])];
    if (orient3d(p.data(), q.data(), r.data(), c.data()) != inner) return false;
    // The face's angle at each corner v as seen from c: between the half-planes (c, v, a)
    // and (c, v, b) about the ray through v.
    for (size_t z = 0; z < 3; ++z) {
      const V3& v = b.vertices[size_t(t[z])];
      const V3 axis = sub3(v, c);
      const double aa = dot(axis, axis);
      auto across = [&](const V3& x) {
        const V3 d = sub3(x, v);
        const double s = dot(d, axis) / aa;
        return V3{d[0] - s * axis[0], d[1] - s * axis[1], d[2] - s * axis[2]};
      };
      const V3 u = across(b.vertices[size_t(t[(z + 1) % 3])]), w = across(b.vertices[size_t(t[(z + 2) % 3])]);
      const V3 n = cross(u, w);
      turn[size_t(t[z])] += std::atan2(std::sqrt(dot(n, n)), dot(u, w));
    }
  }
  // Once around is 2 pi, twice or more at least 4 pi (each face counts positively: it
  // faces away from c), so rounding cannot blur the two.
  for (double a : turn)
    if (!(a < 3 * 3.14159265358979323846)) return false;  // (NaN: overflow, not known)
  return true;
}

}  // namespace

bool faces_outward(const Body& b) {
  if (b.faces.empty()) return true;
  // The volume about a vertex of the body, not the origin: far from the origin the
  // terms about it are offset^2 x size and cancel to noise (a sphere 1e5 of its sizes
  // away came out inward).
  const V3 o = b.vertices[size_t(b.faces[0][0])];
  double vol = 0;
  for (const auto& f : b.faces) {
    const V3 p = sub3(b.vertices[size_t(f[0])], o), q = sub3(b.vertices[size_t(f[1])], o),
             r = sub3(b.vertices[size_t(f[2])], o);
    vol += dot(p, cross(q, r));
  }
  return vol >= 0;
}

std::optional<std::array<int, 2>> self_intersection(const Body& b) {
  return self_intersection(b, EdgeTable(b.vertices.size(), b.faces), faces_outward(b));
}

namespace {

/// The check's parts that need the edge table: whether the body is skipped whole, and the
/// vertices where faces meeting only there need no test.
void shortcuts(const Body& b, const EdgeTable& edges, bool outward, bool& skip, std::vector<char>& convex) {
  skip = b.faces.size() < 2 || star_shaped(b, edges, outward);
  if (skip) return;
  convex = convex_vertices(b, edges, outward);
  const std::vector<char> flat = vertices_with_flat_stars(b, edges);
  for (size_t v = 0; v < convex.size(); ++v) convex[v] = convex[v] || flat[v];
}

/// Pairs of faces (f, g) whose boxes overlap, f in [begin, end), each pair once (found
/// from the face filed finer, or on one level from the lower), but where a shortcut
/// holds, tested exactly; the first that meets.
std::optional<std::array<int, 2>> scan_pairs(const Body& b, const std::vector<char>& convex, const FaceGrid& grid,
                                             int begin, int end, FaceGrid::Marks& marks) {
  std::vector<int> near;
  for (int f = begin; f < end; ++f) {
    V3 lo, hi;
    grid.box(f, lo, hi);
    // (The lookup then skips the finer levels, where a large face's box covers many cells.)
    const int level = grid.level(f);
    grid.near(lo, hi, near, level, marks);
    const auto& tf = b.faces[size_t(f)];
    for (int g : near) {
      if (grid.level(g) == level && g <= f) continue;
      const auto& tg = b.faces[size_t(g)];
      int shared = 0, at = -1;
      for (int x : tf)
        if (x == tg[0] || x == tg[1] || x == tg[2]) { ++shared; at = x; }
      if (shared >= 2) continue;                        // neighbours across an edge meet only along it
      if (shared == 1 && convex[size_t(at)]) continue;  // on a convex cone at their corner, or one to one in a projection
      const V3 pf[3] = {b.vertices[size_t(tf[0])], b.vertices[size_t(tf[1])], b.vertices[size_t(tf[2])]};
      const V3 pg[3] = {b.vertices[size_t(tg[0])], b.vertices[size_t(tg[1])], b.vertices[size_t(tg[2])]};
      if (triangles_meet(tf, pf, tg, pg)) return std::array<int, 2>{std::min(f, g), std::max(f, g)};
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::array<int, 2>> self_intersection(const Body& b, const EdgeTable& edges, bool outward) {
  bool skip = false;
  std::vector<char> convex;
  shortcuts(b, edges, outward, skip, convex);
  if (skip) return std::nullopt;
  const FaceGrid grid(b.vertices, b.faces);
  FaceGrid::Marks marks;
  return scan_pairs(b, convex, grid, 0, int(b.faces.size()), marks);
}

SelfIntersectionScan::SelfIntersectionScan(const Body& b) : b_(b) {
  shortcuts(b, EdgeTable(b.vertices.size(), b.faces), faces_outward(b), skip_, convex_);
  if (!skip_) grid_.emplace(b.vertices, b.faces);
}

std::optional<std::array<int, 2>> SelfIntersectionScan::scan(int begin, int end, FaceGrid::Marks& marks) const {
  if (skip_) return std::nullopt;
  return scan_pairs(b_, convex_, *grid_, begin, end, marks);
}

}  // namespace mr::surface_union
