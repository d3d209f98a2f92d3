#include "union/triangle_intersection.h"

#include "common/parallel_for.h"
#include "union/vec3.h"

#include <algorithm>
#include <cmath>

namespace mr::surface_union {

PairIntersector::PairIntersector(const Soup& soup, PointTable& points, const std::vector<int>& vertex_point)
    : soup_(soup), points_(points), vertex_point_(vertex_point) {}

int PairIntersector::edge_plane_point(int a, int b, int face) {
  if (a > b) std::swap(a, b);
  EFKey key{a, b, face};
  if (const int* id = edge_face_cache_.find(key)) return *id;
  const auto& F = soup_.face[face];
  const int* ready = prepared_index_.find(key);
  int id = points_.insert_on_line(ready ? std::move(prepared_[size_t(*ready)])
                                        : edge_plane_crossing(vp(a), vp(b), vp(F[0]), vp(F[1]), vp(F[2])),
                                  vertex_point_[a], vertex_point_[b]);
  edge_face_cache_.emplace(key, id);
  return id;
}

void PairIntersector::plane_section(int f, const int sign[3], int other, Section& out) {
  const auto& F = soup_.face[f];
  out.n = 0;
  for (int i = 0; i < 3; ++i) {
    if (sign[i] == 0) out.id[out.n++] = vertex_point_[F[i]];
    const int j = (i + 1) % 3;
    if (sign[i] * sign[j] < 0) out.id[out.n++] = edge_plane_point(F[i], F[j], other);
  }
  std::sort(out.id, out.id + out.n);
  out.n = int(std::unique(out.id, out.id + out.n) - out.id);
}

namespace {

/// An axis along which points p and q (distinct) differ, preferring the largest spread.
int spread_axis(const QPoint& p, const QPoint& q) {
  int best = -1;
  double spread = -1;
  for (int k = 0; k < 3; ++k)
    if (compare(p, q, k) != 0 && std::fabs(p.d[k] - q.d[k]) > spread) { spread = std::fabs(p.d[k] - q.d[k]); best = k; }
  return best;
}

void add_result(FaceConstraints& c, int p, int q) {
  if (p == q) c.points.push_back(p);
  else c.segments.push_back({p, q});
}

}  // namespace

// A floating-point filter that only answers "certainly disjoint": the two sections
// are computed in doubles with an error bound, and the pair is rejected when their
// projections on the common line are apart by more than that bound. Anything
// doubtful goes to the exact path, so the filter never changes a decision; it only
// saves building rational points for pairs that do not meet.
bool PairIntersector::sections_surely_apart(int f, const int* st, int g, const int* sx) const {
  const auto& T = soup_.face[f];
  const auto& X = soup_.face[g];
  auto normal = [&](const std::array<int, 3>& F) {
    const V3 &a = soup_.vertex[F[0]], &b = soup_.vertex[F[1]], &c = soup_.vertex[F[2]];
    return cross(sub3(b, a), sub3(c, a));
  };
  const V3 nt = normal(T), nx = normal(X);
  const V3 d = cross(nt, nx);
  const double ld = std::sqrt(dot(d, d)), lt = std::sqrt(dot(nt, nt)), lx = std::sqrt(dot(nx, nx));
  if (!(ld > 1e-6 * lt * lx)) return false;  // nearly parallel planes: decide exactly
  double lo[2], hi[2];
  const std::array<int, 3>* faces[2] = {&T, &X};
  const int* signs[2] = {st, sx};
  const std::array<int, 3>* planes[2] = {&X, &T};
  for (int k = 0; k < 2; ++k) {
    const auto& F = *faces[k];
    const auto& Q = *planes[k];
    const V3& q0 = soup_.vertex[Q[0]];
    const V3 nq = k == 0 ? nx : nt;
    double o[3], err[3];
    for (int i = 0; i < 3; ++i) {
      const V3& p = soup_.vertex[F[i]];
      const V3 r{p[0] - q0[0], p[1] - q0[1], p[2] - q0[2]};
      o[i] = dot(r, nq);
      err[i] = 1e-13 * (std::fabs(r[0] * nq[0]) + std::fabs(r[1] * nq[1]) + std::fabs(r[2] * nq[2]) +
                        std::sqrt(dot(r, r)) * std::sqrt(dot(nq, nq)));
    }
    lo[k] = 1e300;
    hi[k] = -1e300;
    double slack = 0;
    for (int i = 0; i < 3; ++i) {
      const V3& p = soup_.vertex[F[i]];
      if (signs[k][i] == 0) {
        const double x = dot(p, d);
        lo[k] = std::min(lo[k], x);
        hi[k] = std::max(hi[k], x);
      }
      const int j = (i + 1) % 3;
      if (signs[k][i] * signs[k][j] >= 0) continue;
      const double den = o[i] - o[j];
      if (!(std::fabs(den) > 1e6 * (err[i] + err[j]))) return false;
      const V3& q = soup_.vertex[F[j]];
      const double t = o[i] / den;
      const V3 e{q[0] - p[0], q[1] - p[1], q[2] - p[2]};
      const double x = dot(p, d) + t * dot(e, d);
      lo[k] = std::min(lo[k], x);
      hi[k] = std::max(hi[k], x);
      slack = std::max(slack, 1e-5 * std::sqrt(dot(e, e)) * ld + 1e-12 * (std::fabs(dot(p, d)) + std::fabs(dot(e, d))));
    }
    lo[k] -= slack + 1e-12 * std::fabs(lo[k]);
    hi[k] += slack + 1e-12 * std::fabs(hi[k]);
  }
  return lo[0] > hi[1] || lo[1] > hi[0];
}

bool PairIntersector::may_meet(int f, int g, int sx[3], int st[3]) const {
  const auto& T = soup_.face[f];
  const auto& X = soup_.face[g];
  for (int i = 0; i < 3; ++i) sx[i] = orient3d(vp(T[0]), vp(T[1]), vp(T[2]), vp(X[i]));
  if ((sx[0] > 0 && sx[1] > 0 && sx[2] > 0) || (sx[0] < 0 && sx[1] < 0 && sx[2] < 0)) return false;
  if (sx[0] == 0 && sx[1] == 0 && sx[2] == 0) return true;  // coplanar
  for (int i = 0; i < 3; ++i) st[i] = orient3d(vp(X[0]), vp(X[1]), vp(X[2]), vp(T[i]));
  if ((st[0] > 0 && st[1] > 0 && st[2] > 0) || (st[0] < 0 && st[1] < 0 && st[2] < 0)) return false;
  // Both triangles cross the other's plane: each section is a point or a segment on
  // the common line; the intersection is the overlap of the two sections.
  return !sections_surely_apart(f, st, g, sx);
}

std::vector<PairIntersector::Candidate> PairIntersector::prepare(const std::vector<std::pair<int, int>>& pairs) {
  // Per chunk of pairs, those that may meet and the crossings they ask for (an edge that
  // changes side of the other face's plane), then the distinct crossings built in parallel.
  constexpr size_t kChunk = 4096;
  const size_t chunks = (pairs.size() + kChunk - 1) / kChunk;
  std::vector<std::vector<EFKey>> wanted(chunks);
  std::vector<std::vector<Candidate>> meeting(chunks);
  parallel_for(chunks, 1, [&](size_t c) {
    for (size_t k = c * kChunk, end = std::min(pairs.size(), k + kChunk); k < end; ++k) {
      const auto [f, g] = pairs[k];
      int sx[3], st[3] = {0, 0, 0};
      if (!may_meet(f, g, sx, st)) continue;
      Candidate m{int(k), {}, {}};
      for (int i = 0; i < 3; ++i) {
        m.sx[i] = static_cast<signed char>(sx[i]);
        m.st[i] = static_cast<signed char>(st[i]);
      }
      meeting[c].push_back(m);
      if (sx[0] == 0 && sx[1] == 0 && sx[2] == 0) continue;
      for (int side = 0; side < 2; ++side) {
        const auto& F = soup_.face[side == 0 ? f : g];
        const int* sign = side == 0 ? st : sx;
        for (int i = 0; i < 3; ++i) {
          const int j = (i + 1) % 3;
          if (sign[i] * sign[j] < 0)
            wanted[c].push_back({std::min(F[i], F[j]), std::max(F[i], F[j]), side == 0 ? g : f});
        }
      }
    }
  });
  // Each distinct crossing once, in the order first asked for (no sort: the index finds
  // them by key, and which slot holds one changes nothing).
  size_t asked = 0;
  for (const auto& w : wanted) asked += w.size();
  std::vector<EFKey> keys;
  keys.reserve(asked);
  prepared_index_.reserve(asked);
  for (const auto& w : wanted)
    for (const EFKey& key : w)
      if (prepared_index_.emplace(key, int(keys.size())).second) keys.push_back(key);
  wanted.clear();
  prepared_.assign(keys.size(), QPoint());
  // Chunks of 32: a crossing costs ~12k instructions, and rabbit.obj's 584 in chunks of
  // 512 left one thread with most of them.
  parallel_for(keys.size(), 32, [&](size_t k) {
    const auto& F = soup_.face[keys[k].f];
    prepared_[k] = edge_plane_crossing(vp(keys[k].a), vp(keys[k].b), vp(F[0]), vp(F[1]), vp(F[2]));
  });
  std::vector<Candidate> out;
  for (auto& m : meeting) out.insert(out.end(), m.begin(), m.end());
  return out;
}

bool PairIntersector::intersect(int f, int g, CutFaces& cf) {
  int sx[3], st[3];
  if (!may_meet(f, g, sx, st)) return false;
  if (sx[0] == 0 && sx[1] == 0 && sx[2] == 0) return coplanar(f, g, cf);
  return intersect_crossing(f, g, sx, st, cf);
}

bool PairIntersector::intersect(const std::pair<int, int>& pair, const Candidate& c, CutFaces& cf) {
  const int sx[3] = {c.sx[0], c.sx[1], c.sx[2]}, st[3] = {c.st[0], c.st[1], c.st[2]};
  if (sx[0] == 0 && sx[1] == 0 && sx[2] == 0) return coplanar(pair.first, pair.second, cf);
  return intersect_crossing(pair.first, pair.second, sx, st, cf);
}

// Both faces cross the other's plane (signs sx, st) and their sections may overlap.
bool PairIntersector::intersect_crossing(int f, int g, const int sx[3], const int st[3], CutFaces& cf) {
  Section a, b;  // on the stack: two heap vectors per pair were a quarter of this loop
  plane_section(f, st, g, a);
  plane_section(g, sx, f, b);
  if (a.n == 0 || b.n == 0) return false;  // cannot happen with exact signs
  int axis = -1;
  if (a.n > 1) axis = spread_axis(points_[a.id[0]], points_[a.id[1]]);
  else if (b.n > 1) axis = spread_axis(points_[b.id[0]], points_[b.id[1]]);
  if (axis < 0) {  // two single points
    if (a.id[0] != b.id[0]) return false;
    cf[f].points.push_back(a.id[0]);
    cf[g].points.push_back(a.id[0]);
    return true;
  }
  auto less = [&](int p, int q) { return compare(points_[p], points_[q], axis) < 0; };
  if (a.n > 1 && less(a.id[1], a.id[0])) std::swap(a.id[0], a.id[1]);
  if (b.n > 1 && less(b.id[1], b.id[0])) std::swap(b.id[0], b.id[1]);
  const int a_lo = a.id[0], a_hi = a.id[a.n - 1], b_lo = b.id[0], b_hi = b.id[b.n - 1];
  const int lo = less(a_lo, b_lo) ? b_lo : a_lo;
  const int hi = less(a_hi, b_hi) ? a_hi : b_hi;
  const int c = compare(points_[lo], points_[hi], axis);
  if (c > 0) return false;
  const int q = c == 0 ? lo : hi;
  add_result(cf[f], lo, q);
  add_result(cf[g], lo, q);
  return true;
}

namespace {

}  // namespace

int PairIntersector::edge_edge_point(int a, int b, int c, int d, const Projection& pr) {
  // The crossing of two coplanar lines is one point whatever the projection or the
  // order: the key is the unordered pair of undirected edges.
  if (a > b) std::swap(a, b);
  if (c > d) std::swap(c, d);
  EEKey key = a < c || (a == c && b < d) ? EEKey{a, b, c, d} : EEKey{c, d, a, b};
  if (const int* id = edge_edge_cache_.find(key)) return *id;
  const int id = points_.insert_on_line(segment_line_crossing(vp(a), vp(b), vp(c), vp(d), pr.i, pr.j),
                                        vertex_point_[a], vertex_point_[b]);
  points_.mark_on_line(id, vertex_point_[c], vertex_point_[d]);
  edge_edge_cache_.emplace(key, id);
  return id;
}

bool PairIntersector::coplanar(int f, int g, CutFaces& cf) {
  const auto& T = soup_.face[f];
  const auto& X = soup_.face[g];
  // Input vertices only: all predicates run on the doubles (exact with the integer
  // fallback) and the clip points are built with integers, no rational parameter.
  const Projection pr = face_projection(points_[vertex_point_[T[0]]], points_[vertex_point_[T[1]]],
                                        points_[vertex_point_[T[2]]]);
  const int sign_x = orient2d(vp(X[0]), vp(X[1]), vp(X[2]), pr.i, pr.j);
  if (sign_x == 0) return false;  // degenerate face, rejected earlier
  // Clips segment (a, b) against triangle C (orientation sc); appends the part inside.
  auto clip = [&](int va, int vb, const std::array<int, 3>& C, int sc, FaceConstraints& out) {
    const double* a = vp(va);
    const double* b = vp(vb);
    // Points on the segment are ordered by their coordinate along its longest axis.
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (std::fabs(b[k] - a[k]) > std::fabs(b[axis] - a[axis])) axis = k;
    const int dir = b[axis] > a[axis] ? 1 : -1;
    int enter = -1, leave = -1;  // point ids of the clip points
    int side_a[3], side_b[3];
    for (int e = 0; e < 3; ++e) {
      const double* c0 = vp(C[e]);
      const double* c1 = vp(C[(e + 1) % 3]);
      side_a[e] = sc * orient2d(c0, c1, a, pr.i, pr.j);
      side_b[e] = sc * orient2d(c0, c1, b, pr.i, pr.j);
      if (side_a[e] < 0 && side_b[e] < 0) return false;
    }
    // Where the segment's line crosses an edge's line beyond the edge, the crossing lies
    // outside the triangle and can be neither end of a clip that is not empty (the
    // last entry and the first exit lie on the triangle's sides): not built. Most of
    // the crossings of coplanar CAD faces were such points, each built with integers.
    int corner_side[3];
    for (int e = 0; e < 3; ++e) corner_side[e] = orient2d(a, b, vp(C[e]), pr.i, pr.j);
    for (int e = 0; e < 3; ++e) {
      const int sa = side_a[e], sb = side_b[e];
      if (sa >= 0 && sb >= 0) continue;
      if (corner_side[e] * corner_side[(e + 1) % 3] > 0) continue;
      const int x = edge_edge_point(va, vb, C[e], C[(e + 1) % 3], pr);
      if (sa < 0) {  // entering: the last entry counts
        if (enter < 0 || dir * compare(points_[x], points_[enter], axis) > 0) enter = x;
      } else if (leave < 0 || dir * compare(points_[x], points_[leave], axis) < 0) {  // leaving: the first exit counts
        leave = x;
      }
    }
    // An end outside the triangle with no crossing on a side: the segment misses it.
    const bool a_inside = side_a[0] >= 0 && side_a[1] >= 0 && side_a[2] >= 0;
    const bool b_inside = side_b[0] >= 0 && side_b[1] >= 0 && side_b[2] >= 0;
    if ((!a_inside && enter < 0) || (!b_inside && leave < 0)) return false;
    if (enter >= 0 && leave >= 0 && dir * compare(points_[enter], points_[leave], axis) > 0) return false;
    const int p = enter >= 0 ? enter : vertex_point_[va];
    const int q = leave >= 0 ? leave : vertex_point_[vb];
    add_result(out, p, q);
    return true;
  };
  bool any = false;
  FaceConstraints& cft = cf[f];
  FaceConstraints& cfg = cf[g];
  for (int e = 0; e < 3; ++e) any |= clip(X[e], X[(e + 1) % 3], T, 1, cft);
  for (int e = 0; e < 3; ++e) any |= clip(T[e], T[(e + 1) % 3], X, sign_x, cfg);
  if (any) {
    cft.coplanar.push_back(g);
    cfg.coplanar.push_back(f);
  }
  return any;
}

}  // namespace mr::surface_union
