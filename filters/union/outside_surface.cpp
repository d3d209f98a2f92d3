#include "union/outside_surface.h"

#include "common/union_find.h"
#include "union/exact.h"
#include "union/vec3.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

namespace mr::surface_union {

namespace {

/// Generalized winding number of point p with respect to the faces of one body; 0.5
/// (undecided) when p lies exactly on one of the faces.
double winding_number(const Soup& soup, const std::vector<int>& faces, const V3& p) {
  double total = 0;
  for (int f : faces) {
    const V3& A = soup.vertex[soup.face[f][0]];
    const V3& B = soup.vertex[soup.face[f][1]];
    const V3& C = soup.vertex[soup.face[f][2]];
    const V3 a = sub3(A, p), b = sub3(B, p), c = sub3(C, p);
    const double la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b)), lc = std::sqrt(dot(c, c));
    const double num = dot(a, cross(b, c));
    const double den = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
    // On (or within rounding of) the face: this point decides nothing; the caller tries
    // another. Only the choice of test point depends on this bound, not the result.
    if (den <= 0 && (std::fabs(num) <= 1e-9 * la * lb * lc || orient3d(A.data(), B.data(), C.data(), p.data()) == 0))
      return 0.5;
    total += 2 * std::atan2(num, den);
  }
  return total / (4 * 3.14159265358979323846);
}

}  // namespace

Classification classify_outside(const PointTable& points, const std::vector<std::array<int, 3>>& sub,
                                const std::vector<int>& sub_body, const std::vector<int>& sub_face,
                                const std::vector<char>& dropped, const std::vector<int>& kept_copy_body,
                                const Soup& soup) {
  const int ns = int(sub.size());
  Classification out;
  out.kept.assign(ns, 0);
  out.partner.assign(3 * size_t(ns), -1);
  out.line_edge.assign(3 * size_t(ns), 0);
  auto P = [&](int id) -> V3 { return points[id].d; };

  // Half-edges grouped by undirected edge.
  struct HalfEdge {
    uint64_t key;
    int side;  // 3*s + z
  };
  // Ordered by (key, side): first bucketed by the edge's lower point (a counting sort,
  // linear in the half-edges), then each small bucket sorted.
  std::vector<int> bucket_begin(size_t(points.size()) + 1, 0);
  for (int s = 0; s < ns; ++s)
    if (!dropped[s])
      for (int z = 0; z < 3; ++z) ++bucket_begin[std::min(sub[s][z], sub[s][(z + 1) % 3]) + 1];
  std::partial_sum(bucket_begin.begin(), bucket_begin.end(), bucket_begin.begin());
  std::vector<HalfEdge> he(bucket_begin.back());
  {
    std::vector<int> next(bucket_begin.begin(), bucket_begin.end() - 1);
    for (int s = 0; s < ns; ++s) {  // sides in increasing order within each bucket
      if (dropped[s]) continue;
      for (int z = 0; z < 3; ++z) {
        const int u = sub[s][z], w = sub[s][(z + 1) % 3];
        he[next[std::min(u, w)]++] = {(uint64_t(uint32_t(std::min(u, w))) << 32) | uint32_t(std::max(u, w)), 3 * s + z};
      }
    }
  }
  for (size_t p = 0; p + 1 < bucket_begin.size(); ++p)  // insertion sort by key: stable, buckets are small
    for (int i = bucket_begin[p] + 1; i < bucket_begin[p + 1]; ++i)
      for (int j = i; j > bucket_begin[p] && he[j - 1].key > he[j].key; --j) std::swap(he[j - 1], he[j]);
  std::vector<int> group_begin;
  std::vector<int> group_of(3 * size_t(ns), -1);
  for (size_t i = 0; i < he.size(); ++i) {
    if (i == 0 || he[i].key != he[i - 1].key) group_begin.push_back(int(i));
    group_of[he[i].side] = int(group_begin.size()) - 1;
  }
  group_begin.push_back(int(he.size()));

  // Intersection edges and pieces.
  UnionFind uf(ns);
  for (size_t g = 0; g + 1 < group_begin.size(); ++g) {
    const int b = group_begin[g], e = group_begin[g + 1];
    // Where bodies meet; copies lying on a lower body's faces do not count.
    int originals = 0, first_body = -1;
    bool mixed = false;
    for (int i = b; i < e; ++i) {
      const int f = he[i].side / 3;
      if (i > b) uf.unite(f, he[b].side / 3);
      if (kept_copy_body[f] >= 0) continue;
      ++originals;
      if (first_body < 0) first_body = sub_body[f];
      mixed |= sub_body[f] != first_body;
    }
    if (mixed || originals > 2)
      for (int i = b; i < e; ++i) out.line_edge[he[i].side] = 1;
  }

  // The visible neighbour across side 3*s+z.
  // With `inward`, turns the other way among kept faces only (the solid-side
  // neighbour, which keeps bodies that merely touch along an edge apart).
  auto across = [&](int s, int z, bool inward) -> int {
    const int g = group_of[3 * s + z];
    const int b = group_begin[g], e = group_begin[g + 1];
    if (e - b == 2) return he[b].side == 3 * s + z ? he[b + 1].side : he[b].side;
    // Order the faces about the edge exactly: angle from s's half-plane, turning
    // about U->W towards s's outside (right-hand rule). Quadrant 0: (0, pi), 1: pi,
    // 2: (pi, 2 pi), 3: 2 pi (same half-plane as s); within 0 and 2 the orientation
    // of the two half-planes orders them.
    const QPoint& U = points[sub[s][z]];
    const QPoint& W = points[sub[s][(z + 1) % 3]];
    const QPoint& X = points[sub[s][(z + 2) % 3]];
    auto third = [&](int side) -> const QPoint& { return points[sub[side / 3][(side % 3 + 2) % 3]]; };
    // s lies exactly in the plane of its input face and, like every piece of a
    // re-triangulated face, has that face's orientation (the triangulation only makes
    // and flips into strictly positive triangles): the side of s's plane a point lies
    // on is its side of the input face's plane. Decided there, on exact doubles of a
    // proper triangle, instead of on the (often sliver) piece's rational corners.
    const auto& input = soup.face[sub_face[s]];
    const QPoint A = make_point(soup.vertex[input[0]]), B = make_point(soup.vertex[input[1]]),
                 C = make_point(soup.vertex[input[2]]);
    auto quadrant = [&](int side) {
      // Pieces of the same input face lie in one plane, on opposite sides of the edge.
      if (sub_face[side / 3] == sub_face[s]) return 1;
      const int o = orient3d(A, B, C, third(side));
      if (o > 0) return 0;
      if (o < 0) return 2;
      return perpendicular_dot_sign(U, W, X, third(side)) < 0 ? 1 : 3;
    };
    auto before = [&](int a, int qa, int c, int qc) {  // a comes before c
      if (qa != qc) return qa < qc;
      // (Same input face and same side of the edge cannot happen: a planar triangulation.)
      const int o = (qa == 0 || qa == 2) ? orient3d(U, W, third(a), third(c)) : 0;
      if (o != 0) return o > 0;
      // Coincident half-planes (copies of one face in different bodies): the lower body's first.
      return sub_body[a / 3] < sub_body[c / 3];
    };
    int best = -1, best_q = 0;
    for (int i = b; i < e; ++i) {
      const int side = he[i].side;
      if (side == 3 * s + z) continue;
      if (inward && !out.kept[side / 3]) continue;
      const int q = quadrant(side);
      // Outward: the first face met; inward (turning the other way): the last.
      if (best < 0 || (inward ? before(best, best_q, side, q) : before(side, q, best, best_q))) {
        best = side;
        best_q = q;
      }
    }
    return best;
  };

  auto lexicographically_greater = [](const QPoint& a, const QPoint& b) {
    for (int k = 0; k < 3; ++k) {
      const int c = compare(a, b, k);
      if (c != 0) return c > 0;
    }
    return false;
  };
  // Pieces, numbered in the order of their first face (the per-piece tables below are
  // as long as the pieces, not the faces).
  std::vector<int> piece_of(ns, -1);
  int pieces = 0;
  {
    std::vector<int> piece_of_root(ns, -1);
    for (int s = 0; s < ns; ++s) {
      if (dropped[s]) continue;
      const int r = uf.find(s);
      if (piece_of_root[r] < 0) piece_of_root[r] = pieces++;
      piece_of[s] = piece_of_root[r];
    }
  }
  // Extreme vertex of each piece (largest x, then y, z) and the face there seen best from +x.
  std::vector<int> extreme(pieces, -1);  // point index
  for (int s = 0; s < ns; ++s) {
    if (dropped[s]) continue;
    const int r = piece_of[s];
    for (int z = 0; z < 3; ++z) {
      const int p = sub[s][z];
      if (extreme[r] < 0 || lexicographically_greater(points[p], points[extreme[r]])) extreme[r] = p;
    }
  }
  out.pieces = pieces;
  // Faces at the extreme vertex: the one facing +x most is outside. Decided exactly:
  // bodies touching there can have faces tilted against each other by 1e-16.
  auto exact_normal = [&](int s, mpq_class* n) {
    const QPoint &a = points[sub[s][0]], &b = points[sub[s][1]], &c = points[sub[s][2]];
    mpq_class u[3], v[3];
    for (int k = 0; k < 3; ++k) { u[k] = b.q(k) - a.q(k); v[k] = c.q(k) - a.q(k); }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
  };
  // n_x / |n| of face a larger than of face b: compare n_x |n_x| / |n|^2 exactly.
  auto faces_more_towards_x = [&](int a, int b) {
    mpq_class na[3], nb[3];
    exact_normal(a, na);
    exact_normal(b, nb);
    const mpq_class la = na[0] * na[0] + na[1] * na[1] + na[2] * na[2];
    const mpq_class lb = nb[0] * nb[0] + nb[1] * nb[1] + nb[2] * nb[2];
    if (sgn(la) == 0) return false;
    if (sgn(lb) == 0) return true;
    return na[0] * abs(na[0]) * lb > nb[0] * abs(nb[0]) * la;
  };
  std::vector<int> start(pieces, -1);

  std::vector<std::set<int>> piece_bodies(pieces);
  auto at_extreme = [&](int s, int r) {
    return sub[s][0] == extreme[r] || sub[s][1] == extreme[r] || sub[s][2] == extreme[r];
  };
  // (Neighbouring faces mostly share piece and body: a pair is only looked up when it differs
  // from the last one.)
  std::vector<std::set<int>> pieces_of_body(soup.body_count);
  for (int s = 0, last_piece = -1, last_body = -1; s < ns; ++s) {
    if (dropped[s] || (piece_of[s] == last_piece && sub_body[s] == last_body)) continue;
    last_piece = piece_of[s];
    last_body = sub_body[s];
    piece_bodies[last_piece].insert(last_body);
    pieces_of_body[last_body].insert(last_piece);
  }
  // A body whose faces were dropped as copies of a piece's faces lies on that piece:
  // it belongs to the piece for the inside test below.
  {
    for (int s = 0; s < ns; ++s)
      if (kept_copy_body[s] >= 0)
        for (int r : pieces_of_body[kept_copy_body[s]]) piece_bodies[r].insert(sub_body[s]);
  }
  // The start face lies on the piece's outer edge: among the edges at the extreme vertex,
  // the one closest to perpendicular to x (largest d_x / |d|, all d_x <= 0). The directions
  // between it and +x cross no face, so the faces around it that bound that wedge are
  // outside, and of those the one whose normal leans most towards +x faces it. Comparing
  // the normals of all faces at the vertex instead can pick a face tilted by 1e-16 that is
  // inside another body touching there (spheres sharing a pole).
  std::vector<int> outer_end(pieces, -1);  // the outer edge's other point
  auto closer_to_perpendicular = [&](int p, int u, int w) {  // edge p-u before p-w
    mpq_class du[3], dw[3];
    for (int k = 0; k < 3; ++k) { du[k] = points[u].q(k) - points[p].q(k); dw[k] = points[w].q(k) - points[p].q(k); }
    const mpq_class lu = du[0] * du[0] + du[1] * du[1] + du[2] * du[2];
    const mpq_class lw = dw[0] * dw[0] + dw[1] * dw[1] + dw[2] * dw[2];
    return du[0] * du[0] * lw < dw[0] * dw[0] * lu;  // |du_x| / |du| < |dw_x| / |dw|
  };
  for (int s = 0; s < ns; ++s) {
    if (dropped[s]) continue;
    const int r = piece_of[s];
    if (!at_extreme(s, r)) continue;
    for (int z = 0; z < 3; ++z) {
      const int u = sub[s][z];
      if (u == extreme[r] || u == outer_end[r]) continue;
      if (outer_end[r] < 0 || closer_to_perpendicular(extreme[r], u, outer_end[r])) outer_end[r] = u;
    }
  }
  for (int s = 0; s < ns; ++s) {
    if (dropped[s]) continue;
    const int r = piece_of[s];
    if (!at_extreme(s, r)) continue;
    if (sub[s][0] != outer_end[r] && sub[s][1] != outer_end[r] && sub[s][2] != outer_end[r]) continue;
    if (start[r] < 0 || faces_more_towards_x(s, start[r])) start[r] = s;
  }
  // Faces of each body, for the point-in-body test.
  std::vector<std::vector<int>> body_faces(soup.body_count);
  std::vector<std::array<double, 6>> body_box(soup.body_count, {1e300, 1e300, 1e300, -1e300, -1e300, -1e300});
  for (int f = 0; f < int(soup.face.size()); ++f) {
    body_faces[soup.body[f]].push_back(f);
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) {
        body_box[soup.body[f]][k] = std::min(body_box[soup.body[f]][k], soup.vertex[soup.face[f][c]][k]);
        body_box[soup.body[f]][k + 3] = std::max(body_box[soup.body[f]][k + 3], soup.vertex[soup.face[f][c]][k]);
      }
  }
  // Test points of a piece: the centroids of its largest face and of a few others, and
  // its extreme vertex. A piece never crosses another body, but it may touch one (at its
  // extreme vertex, say) or lie on one (a coincident copy): a point on the other body's
  // surface gives a winding number near 1/2 and decides nothing, so the first point with
  // a clear answer decides; with none the piece only touches and stays.
  std::vector<std::vector<V3>> samples(pieces);
  std::vector<double> largest_area(pieces, -1);
  std::vector<V3> largest_centroid(pieces);
  for (int s = 0; s < ns; ++s) {
    if (dropped[s]) continue;
    const int r = piece_of[s];
    const V3 n = cross(sub3(P(sub[s][1]), P(sub[s][0])), sub3(P(sub[s][2]), P(sub[s][0])));
    V3 c{0, 0, 0};
    for (int z = 0; z < 3; ++z)
      for (int k = 0; k < 3; ++k) c[k] += P(sub[s][z])[k] / 3;
    if (dot(n, n) > largest_area[r]) { largest_area[r] = dot(n, n); largest_centroid[r] = c; }
    if (samples[r].size() < 4 && dot(n, n) > 0) samples[r].push_back(c);
  }
  std::vector<int> stack;
  for (int r = 0; r < pieces; ++r) {
    std::vector<V3> points_to_test{largest_centroid[r], P(extreme[r])};
    points_to_test.insert(points_to_test.end(), samples[r].begin(), samples[r].end());
    bool inside = false;
    for (int b = 0; b < soup.body_count && !inside; ++b) {
      if (piece_bodies[r].count(b)) continue;
      const auto& bb = body_box[b];
      for (const V3& p : points_to_test) {
        if (p[0] < bb[0] || p[1] < bb[1] || p[2] < bb[2] || p[0] > bb[3] || p[1] > bb[4] || p[2] > bb[5]) break;
        const double w = winding_number(soup, body_faces[b], p);
        if (std::fabs(w - 0.5) > 0.25) {
          inside = w > 0.5;
          break;
        }
      }
    }
    if (inside) { ++out.pieces_inside; continue; }
    const int s0 = start[r];
    if (s0 < 0) continue;  // no usable face at the extreme vertex (all degenerate): leave the piece out
    out.kept[s0] = 1;
    stack.push_back(s0);
    while (!stack.empty()) {
      const int s = stack.back();
      stack.pop_back();
      for (int z = 0; z < 3; ++z) {
        const int side = across(s, z, false);
        if (side < 0) {  // an edge with one face: the arrangement is not closed here
          ++out.open_sides;
          continue;
        }
        out.partner[3 * s + z] = side;
        const int t = side / 3, y = side % 3;
        if (sub[t][y] != sub[s][(z + 1) % 3]) ++out.orientation_conflicts;
        if (!out.kept[t]) { out.kept[t] = 1; stack.push_back(t); }
      }
    }
  }
  // Shells: at edges where more than two kept faces meet, pair each with its
  // solid-side neighbour instead.
  for (int s = 0; s < ns; ++s) {
    if (!out.kept[s]) continue;
    for (int z = 0; z < 3; ++z) {
      const int g = group_of[3 * s + z];
      int kept_here = 0;
      for (int i = group_begin[g]; i < group_begin[g + 1]; ++i) kept_here += out.kept[he[i].side / 3];
      if (kept_here > 2) {
        const int side = across(s, z, true);
        if (side >= 0) out.partner[3 * s + z] = side;
      }
    }
  }
  return out;
}

}  // namespace mr::surface_union
