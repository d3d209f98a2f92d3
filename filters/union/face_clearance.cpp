#include "union/face_clearance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "union/exact.h"
#include "union/vec3.h"

namespace mr::surface_union {

namespace {

/// Closed segment (p, q) against the closed triangle (a, b, c) in their common plane,
/// seen across the triangle's largest normal component. Each 2D orientation is taken
/// once: a corner-inside test and the side-crossing tests share o(x, y, p) and
/// o(x, y, q) for the triangle's sides (x, y), and neighbouring sides share o(p, q, x);
/// 10 predicates where the tests one by one took up to 19 (CAD creases run this often).
bool coplanar_segment_meets_triangle(const V3& p, const V3& q, const V3& a, const V3& b, const V3& c) {
  const V3 n = cross(sub3(b, a), sub3(c, a));
  int k = 0;
  for (int t = 1; t < 3; ++t)
    if (std::fabs(n[t]) > std::fabs(n[k])) k = t;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  // Doubles are exact inputs: the filtered 2D orientation with an integer fallback.
  auto o = [&](const V3& x, const V3& y, const V3& z) { return orient2d(x.data(), y.data(), z.data(), i, j); };
  const int sign = o(a, b, c);  // orientation of the triangle in this projection
  const V3* T[3] = {&a, &b, &c};
  int side_p[3], side_q[3];  // o(T[e], T[e + 1], p) and the same for q
  for (int e = 0; e < 3; ++e) {
    side_p[e] = o(*T[e], *T[(e + 1) % 3], p);
    side_q[e] = o(*T[e], *T[(e + 1) % 3], q);
  }
  auto inside = [&](const int* side) { return sign * side[0] >= 0 && sign * side[1] >= 0 && sign * side[2] >= 0; };
  if (inside(side_p) || inside(side_q)) return true;
  auto on_segment = [&](const V3& x, const V3& y, const V3& z) {  // z on closed xy, collinear
    for (int m : {i, j})
      if (std::min(x[m], y[m]) > z[m] || std::max(x[m], y[m]) < z[m]) return false;
    return true;
  };
  int across[3];  // o(p, q, T[e])
  for (int e = 0; e < 3; ++e) across[e] = o(p, q, *T[e]);
  for (int e = 0; e < 3; ++e) {
    const V3 &X = *T[e], &Y = *T[(e + 1) % 3];
    const int o1 = across[e], o2 = across[(e + 1) % 3], o3 = side_p[e], o4 = side_q[e];
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    if ((o1 == 0 && on_segment(p, q, X)) || (o2 == 0 && on_segment(p, q, Y)) || (o3 == 0 && on_segment(X, Y, p)) ||
        (o4 == 0 && on_segment(X, Y, q)))
      return true;
  }
  return false;
}

/// Segment (p, q) meets the closed triangle (a, b, c) (exact; coplanar counts as a hit).
/// sp and sq are the exact sides of p and q of the triangle's plane,
/// orient3d(a, b, c, p) and orient3d(a, b, c, q): the caller has them already (the
/// plane sides that decided the pair so far), and recomputing them was a third of
/// this test's cost on CAD creases, where they are zero.
bool segment_meets_triangle(const V3& p, const V3& q, int sp, int sq, const V3& a, const V3& b, const V3& c) {
  // Boxes apart (exact comparisons): no predicate needed. The segment is often a side
  // lying in the plane of a long face, far from this triangle's part of it.
  for (int k = 0; k < 3; ++k)
    if (std::max(p[k], q[k]) < std::min({a[k], b[k], c[k]}) || std::min(p[k], q[k]) > std::max({a[k], b[k], c[k]}))
      return false;
  if (sp * sq > 0) return false;
  if (sp == 0 && sq == 0) return coplanar_segment_meets_triangle(p, q, a, b, c);
  const int s1 = orient3d(p.data(), q.data(), a.data(), b.data());
  const int s2 = orient3d(p.data(), q.data(), b.data(), c.data());
  const int s3 = orient3d(p.data(), q.data(), c.data(), a.data());
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

/// Decides in the projection on the coordinate plane across axis k (both projected
/// triangles non-degenerate, so each is mapped one to one): true when F and G meet at
/// most in the shared corner (sf, sg; -1: none). Without a shared corner: an edge line
/// with the other triangle strictly outside. With one: the two corner sectors at the
/// shared corner have no side ray inside the other (convex sectors below 180 degrees
/// then meet only at the apex). Exact on the doubles, and cheaper than the 3D tests:
/// it decides neighbours in one plane (or nearly), where 3D orientations are zero or
/// close to it.
bool separated_in_projection(const V3 F[3], const V3 G[3], int sf, int sg, int k) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  auto o = [&](const V3& x, const V3& y, const V3& z) { return orient2d(x.data(), y.data(), z.data(), i, j); };
  const int sides[2] = {o(F[0], F[1], F[2]), o(G[0], G[1], G[2])};
  if (sides[0] == 0 || sides[1] == 0) return false;
  if (sf >= 0) {
    const V3& s = F[sf];
    for (int side = 0; side < 2; ++side) {
      const V3* A = side == 0 ? F : G;
      const V3* B = side == 0 ? G : F;
      const int sa = sides[side], ca = side == 0 ? sf : sg, cb = side == 0 ? sg : sf;
      const V3 &a1 = A[(ca + 1) % 3], &a2 = A[(ca + 2) % 3];
      for (const V3* ray : {&B[(cb + 1) % 3], &B[(cb + 2) % 3]})
        if (sa * o(s, a1, *ray) >= 0 && sa * o(s, *ray, a2) >= 0) return false;
    }
    return true;
  }
  for (int side = 0; side < 2; ++side) {
    const V3* A = side == 0 ? F : G;
    const V3* B = side == 0 ? G : F;
    const int sa = sides[side];
    for (int z = 0; z < 3; ++z) {
      // B in the closed outer half-plane of A's edge line; corners of B on the line
      // (collinear cuts along one straight intersection segment) must lie beyond the
      // edge's ends, compared along the line in the coordinate that changes most on it.
      const V3 &e0 = A[z], &e1 = A[(z + 1) % 3];
      const int c = std::fabs(e1[i] - e0[i]) >= std::fabs(e1[j] - e0[j]) ? i : j;
      const double lo = std::min(e0[c], e1[c]), hi = std::max(e0[c], e1[c]);
      bool separated = true, below = false, above = false;
      for (int m = 0; m < 3 && separated; ++m) {
        const int om = sa * o(e0, e1, B[m]);
        if (om > 0) separated = false;
        else if (om == 0) {
          below |= B[m][c] < lo;
          above |= B[m][c] > hi;
          separated = B[m][c] < lo || B[m][c] > hi;
        }
      }
      if (separated && !(below && above)) return true;
    }
  }
  return false;
}

/// Sides of the points B[0..2] of A's plane as far as a floating-point filter tells:
/// orient3d(A[0], A[1], A[2], B[i]) where certain, kUnknown where not. B's corner
/// `in_plane` (the shared corner, or -1) is in the plane without a test. The normal is
/// computed once for the three; the same filter bound as orient3d (this is its
/// expansion along d - a). Returns false when some side is unknown.
constexpr int kUnknown = 2;
bool filtered_plane_sides(const V3 A[3], const V3 B[3], int in_plane, int out[3]) {
  const double bx = A[1][0] - A[0][0], by = A[1][1] - A[0][1], bz = A[1][2] - A[0][2];
  const double cx = A[2][0] - A[0][0], cy = A[2][1] - A[0][1], cz = A[2][2] - A[0][2];
  const double n0 = by * cz - bz * cy, n1 = bz * cx - bx * cz, n2 = bx * cy - by * cx;
  const double m0 = std::fabs(by * cz) + std::fabs(bz * cy), m1 = std::fabs(bz * cx) + std::fabs(bx * cz),
               m2 = std::fabs(bx * cy) + std::fabs(by * cx);
  bool sure = true;
  for (int i = 0; i < 3; ++i) {
    if (i == in_plane) {
      out[i] = 0;
      continue;
    }
    const double dx = B[i][0] - A[0][0], dy = B[i][1] - A[0][1], dz = B[i][2] - A[0][2];
    const double det = dx * n0 + dy * n1 + dz * n2;
    const double bound = 1e-14 * (std::fabs(dx) * m0 + std::fabs(dy) * m1 + std::fabs(dz) * m2);
    out[i] = det > bound ? 1 : det < -bound ? -1 : kUnknown;
    sure &= out[i] != kUnknown;
  }
  return sure;
}

/// The sides the filter left unknown, exactly.
void resolve_plane_sides(const V3 A[3], const V3 B[3], int sides[3]) {
  for (int i = 0; i < 3; ++i)
    if (sides[i] == kUnknown) sides[i] = orient3d(A[0].data(), A[1].data(), A[2].data(), B[i].data());
}

/// F and G, sharing no corner, each with one corner strictly on one side of the other's
/// plane and two strictly on the other (sides known exactly: sf are F's corners of G's
/// plane, sg G's of F's). Each then cuts the line common to the planes in a segment,
/// and they meet exactly when the segments overlap: two orientations decide it
/// (Devillers and Guigue 2002). p1 and p2 are the lone corners, the others taken in the
/// face's turning order; swapping a face's other two corners turns its plane over, so
/// that both lone corners lie on the positive side of the other plane. Along the common
/// line (oriented as n1 x n2) F's segment then runs from its crossing on p1r1 to the one
/// on p1q1, and G's from its crossing on p2q2 to the one on p2r2; orient3d(p1, q1, p2, q2)
/// is the sign of G's start minus F's end, orient3d(p1, r1, p2, r2) that of G's end
/// minus F's start (taken below with its last two points swapped, so both must be <= 0).
bool straddling_triangles_meet(const V3 F[3], const V3 G[3], const int sf[3], const int sg[3]) {
  const int i1 = sf[0] == sf[1] ? 2 : sf[0] == sf[2] ? 1 : 0;
  const int i2 = sg[0] == sg[1] ? 2 : sg[0] == sg[2] ? 1 : 0;
  const V3 *p1 = &F[i1], *q1 = &F[(i1 + 1) % 3], *r1 = &F[(i1 + 2) % 3];
  const V3 *p2 = &G[i2], *q2 = &G[(i2 + 1) % 3], *r2 = &G[(i2 + 2) % 3];
  if (sf[i1] < 0) std::swap(q2, r2);
  if (sg[i2] < 0) std::swap(q1, r1);
  return orient3d(p1->data(), q1->data(), p2->data(), q2->data()) <= 0 &&
         orient3d(p1->data(), r1->data(), r2->data(), p2->data()) <= 0;
}

/// All of B but the shared corner strictly on one side of A's plane (sides known).
bool strictly_one_side(const int sides[3], int shared) {
  int pos = 0, neg = 0;
  for (int i = 0; i < 3; ++i) { pos += sides[i] == 1; neg += sides[i] == -1; }
  return pos + shared == 3 || neg + shared == 3;
}


}  // namespace

bool triangles_meet(const std::array<int, 3>& a, const V3 F[3], const std::array<int, 3>& b, const V3 G[3]) {
  int shared = 0, sf = -1, sg = -1;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a[i] == b[j] || F[i] == G[j]) { ++shared; sf = i; sg = j; }
  if (shared >= 2) return false;  // neighbours across an edge
  // Separating planes: a face strictly on one side of the other's plane (but for a
  // shared corner) cannot meet it (neighbours on a curved surface). First what the
  // floating-point filter tells; the exact predicates only where it cannot.
  int sides[2][3];
  bool sure[2];
  for (int k = 0; k < 2; ++k) {
    const int in_plane = shared == 1 ? (k == 0 ? sg : sf) : -1;  // B's shared corner
    sure[k] = filtered_plane_sides(k == 0 ? F : G, k == 0 ? G : F, in_plane, sides[k]);
    if (sure[k] && strictly_one_side(sides[k], shared)) return false;
  }
  // Each strictly across the other's plane (sides certain, none zero when no corner
  // is shared): two more orientations decide.
  if (shared == 0 && sure[0] && sure[1]) return straddling_triangles_meet(F, G, sides[1], sides[0]);
  // Nearly coplanar neighbours (pieces of one input face, slivers): the projection
  // decides most of them on the doubles, cheaper than exact plane sides.
  const int kf = largest_normal_axis(F), kg = largest_normal_axis(G);
  const int cf = shared == 1 ? sf : -1, cg = shared == 1 ? sg : -1;
  bool projection_tried = false;
  if (!sure[0] || !sure[1]) {
    if (separated_in_projection(F, G, cf, cg, kf) || (kg != kf && separated_in_projection(F, G, cf, cg, kg)))
      return false;
    projection_tried = true;
  }
  for (int k = 0; k < 2; ++k) {
    const V3* A = k == 0 ? F : G;
    const V3* B = k == 0 ? G : F;
    int pos = 0, neg = 0, zero = 0, on[3];
    resolve_plane_sides(A, B, sides[k]);
    for (int i = 0; i < 3; ++i) {
      const int o = sides[k][i];
      pos += o > 0;
      neg += o < 0;
      if (o == 0) on[zero++] = i;
    }
    // B touches A's plane from one side (faces along a crease): only its corner or
    // side in the plane can meet A.
    if (shared == 0 && (pos == 0 || neg == 0) && (zero == 1 || zero == 2))
      return segment_meets_triangle(B[on[0]], B[on[zero - 1]], 0, 0, A[0], A[1], A[2]);
    // The same with a shared corner s: B's side (s, x) in A's plane meets A beyond s
    // exactly when it leaves s into A's corner sector (seen across A's largest normal
    // component, where A is not degenerate).
    if (shared == 1 && (pos == 0 || neg == 0) && zero == 2) {
      const int ca = k == 0 ? sf : sg, cb = k == 0 ? sg : sf;
      const V3& x = B[on[0]] == B[cb] ? B[on[1]] : B[on[0]];
      const int ka = largest_normal_axis(A), i = (ka + 1) % 3, j = (ka + 2) % 3;
      auto o = [&](const V3& p, const V3& q, const V3& r) { return orient2d(p.data(), q.data(), r.data(), i, j); };
      const int sa = o(A[0], A[1], A[2]);
      const V3 &s = A[ca], &a1 = A[(ca + 1) % 3], &a2 = A[(ca + 2) % 3];
      return sa * o(s, a1, x) >= 0 && sa * o(s, x, a2) >= 0;
    }
    if (zero == 3) break;  // coplanar
    // All but the shared corner strictly on one side (the shared corner has o == 0).
    if ((pos + shared == 3 || neg + shared == 3) && (shared == 0 || zero == 1)) return false;
  }
  // Then in a projection (across F's, then G's largest normal component): neighbours
  // in one plane or across a crease.
  if (!projection_tried &&
      (separated_in_projection(F, G, cf, cg, kf) || (kg != kf && separated_in_projection(F, G, cf, cg, kg))))
    return false;
  // The side tests below take the corners' exact plane sides: sides[0] are G's of
  // F's plane, sides[1] F's of G's (the loop above may have stopped before G's plane).
  resolve_plane_sides(F, G, sides[0]);
  resolve_plane_sides(G, F, sides[1]);
  auto f_side_meets_g = [&](int e, int e1) {
    return segment_meets_triangle(F[e], F[e1], sides[1][e], sides[1][e1], G[0], G[1], G[2]);
  };
  auto g_side_meets_f = [&](int e, int e1) {
    return segment_meets_triangle(G[e], G[e1], sides[0][e], sides[0][e1], F[0], F[1], F[2]);
  };
  if (shared == 1)  // only the edges opposite the shared corner can cross the other face
    return f_side_meets_g((sf + 1) % 3, (sf + 2) % 3) || g_side_meets_f((sg + 1) % 3, (sg + 2) % 3);
  for (int e = 0; e < 3; ++e)
    if (f_side_meets_g(e, (e + 1) % 3) || g_side_meets_f(e, (e + 1) % 3)) return true;
  return false;
}

int largest_normal_axis(const V3 T[3]) {
  const V3 n = cross(sub3(T[1], T[0]), sub3(T[2], T[0]));
  int k = 0;
  for (int t = 1; t < 3; ++t)
    if (std::fabs(n[t]) > std::fabs(n[k])) k = t;
  return k;
}

bool flat_convex_quad(const V3& u, const V3& v, const V3& c, const V3& d) {
  if (orient3d(u.data(), v.data(), c.data(), d.data()) != 0) return false;
  // In the plane, seen across any axis where (u, v, c) does not degenerate: both old
  // and both new triangles turn the same way, so the diagonals cross inside.
  const V3 T[3] = {u, v, c};
  const int k = largest_normal_axis(T), i = (k + 1) % 3, j = (k + 2) % 3;
  auto o = [&](const V3& p, const V3& q, const V3& r) { return orient2d(p.data(), q.data(), r.data(), i, j); };
  const int s = o(u, v, c);
  return s != 0 && o(v, u, d) == s && o(u, d, c) == s && o(d, v, c) == s;
}

FaceGrid::FaceGrid(const std::vector<V3>& vertices, const std::vector<std::array<int, 3>>& faces)
    : vertices_(vertices), faces_(faces), boxes_(faces.size()), level_(faces.size(), -1) {
  if (faces.empty()) return;
  V3 lo_all{1e300, 1e300, 1e300}, hi_all{-1e300, -1e300, -1e300};
  std::vector<double> sizes;
  sizes.reserve(faces.size());
  for (int f = 0; f < int(faces.size()); ++f) {
    V3 lo, hi;
    box(f, lo, hi);
    for (int k = 0; k < 3; ++k) { lo_all[k] = std::min(lo_all[k], lo[k]); hi_all[k] = std::max(hi_all[k], hi[k]); }
    sizes.push_back(std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}));
  }
  // The finest level fits the small faces (slivers along the cuts are much smaller
  // than the median CAD face); each coarser level has 4x larger cells.
  std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
  const double extent = std::max({hi_all[0] - lo_all[0], hi_all[1] - lo_all[1], hi_all[2] - lo_all[2]});
  cell_ = std::max({2 * sizes[sizes.size() / 2], extent / 4096, 1e-300});
  origin_ = lo_all;
  cell_index_.reserve(2 * faces.size());
  heads_.reserve(2 * faces.size());
  entries_.reserve(3 * faces.size());
  for (int f = 0; f < int(faces.size()); ++f) add(f);
}

void FaceGrid::box(int f, V3& lo, V3& hi) const {
  const auto& t = faces_[f];
  lo = hi = vertices_[t[0]];
  for (int z = 1; z < 3; ++z)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], vertices_[t[z]][k]);
      hi[k] = std::max(hi[k], vertices_[t[z]][k]);
    }
}

int64_t FaceGrid::cell_of(double x, int k, int level) const {
  return int64_t(std::floor((x - origin_[k]) / (cell_ * double(int64_t(1) << (2 * level)))));
}

void FaceGrid::remove(int f) {
  if (level_[f] < 0) return;
  const int level = level_[f];
  level_[f] = -1;
  const auto& [lo, hi] = boxes_[f];
  int64_t a[3], b[3];
  for (int k = 0; k < 3; ++k) { a[k] = cell_of(lo[k], k, level); b[k] = cell_of(hi[k], k, level); }
  for (int64_t i = a[0]; i <= b[0]; ++i)
    for (int64_t j = a[1]; j <= b[1]; ++j)
      for (int64_t k = a[2]; k <= b[2]; ++k) {
        int* head = head_of(key(i, j, k, level));
        if (!head) continue;
        for (int* link = head; *link >= 0; link = &entries_[size_t(*link)].next)
          if (entries_[size_t(*link)].face == f) {
            const int e = *link;
            *link = entries_[size_t(e)].next;
            entries_[size_t(e)].next = free_entry_;
            free_entry_ = e;
            break;
          }
      }
}

int* FaceGrid::head_of(int64_t key) {
  const int* slot = cell_index_.find(key);
  return slot ? &heads_[size_t(*slot)] : nullptr;
}

const int* FaceGrid::head_of(int64_t key) const {
  const int* slot = cell_index_.find(key);
  return slot ? &heads_[size_t(*slot)] : nullptr;
}

int& FaceGrid::head_or_new(int64_t key) {
  const auto [slot, added] = cell_index_.emplace(key, int(heads_.size()));
  if (added) heads_.push_back(-1);
  return heads_[size_t(slot)];
}

void FaceGrid::add(int f) {
  V3 lo, hi;
  box(f, lo, hi);
  // The finest level where the face's box is no larger than a cell: at most 2 cells a side.
  const double size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  int level = 0;
  while (level < kLevels - 1 && size > cell_ * double(int64_t(1) << (2 * level))) ++level;
  int64_t a[3], b[3];
  for (int k = 0; k < 3; ++k) { a[k] = cell_of(lo[k], k, level); b[k] = cell_of(hi[k], k, level); }
  if (level_[f] == level) {
    // Still in the same cells (most moves of the sliver step are small): only the box changes.
    const auto& [old_lo, old_hi] = boxes_[f];
    bool same = true;
    for (int k = 0; k < 3; ++k)
      same = same && cell_of(old_lo[k], k, level) == a[k] && cell_of(old_hi[k], k, level) == b[k];
    if (same) {
      boxes_[f] = {lo, hi};
      return;
    }
  }
  remove(f);  // stale entries would make every later lookup longer
  boxes_[f] = {lo, hi};
  levels_used_ = std::max(levels_used_, level + 1);
  level_[f] = level;
  level_faces_[level].push_back(f);  // may repeat: lookups see each face once
  for (int64_t i = a[0]; i <= b[0]; ++i)
    for (int64_t j = a[1]; j <= b[1]; ++j)
      for (int64_t k = a[2]; k <= b[2]; ++k) {
        int& head = head_or_new(key(i, j, k, level));
        int e = free_entry_;
        if (e >= 0) free_entry_ = entries_[size_t(e)].next;
        else {
          e = int(entries_.size());
          entries_.push_back({});
        }
        entries_[size_t(e)] = {f, head};
        head = e;
      }
}

void FaceGrid::near(const V3& lo, const V3& hi, std::vector<int>& out, int from_level, Marks& marks) const {
  out.clear();
  if (marks.seen.size() < faces_.size()) marks.seen.resize(faces_.size(), 0);  // (stamps only grow: old marks are below)
  if (marks.stamp == std::numeric_limits<int>::max()) {  // (marks kept by a thread for many unions)
    std::fill(marks.seen.begin(), marks.seen.end(), 0);
    marks.stamp = 0;
  }
  const int stamp = ++marks.stamp;
  std::vector<int>& seen = marks.seen;
  auto consider = [&](int g) {
    if (seen[size_t(g)] == stamp || level_[size_t(g)] < 0) return;
    seen[size_t(g)] = stamp;
    const auto& gb = boxes_[g];
    for (int c = 0; c < 3; ++c)
      if (gb[1][c] < lo[c] || hi[c] < gb[0][c]) return;
    out.push_back(g);
  };
  for (int level = std::max(from_level, 0); level < levels_used_; ++level) {
    int64_t a[3], b[3];
    for (int k = 0; k < 3; ++k) { a[k] = cell_of(lo[k], k, level); b[k] = cell_of(hi[k], k, level); }
    // A long query box on a fine level: fewer faces there than cells to look up.
    const double cells = double(b[0] - a[0] + 1) * double(b[1] - a[1] + 1) * double(b[2] - a[2] + 1);
    if (cells > double(level_faces_[level].size())) {
      for (int g : level_faces_[level]) consider(g);
      continue;
    }
    for (int64_t i = a[0]; i <= b[0]; ++i)
      for (int64_t j = a[1]; j <= b[1]; ++j)
        for (int64_t k = a[2]; k <= b[2]; ++k) {
          if (const int* head = head_of(key(i, j, k, level)))
            for (int e = *head; e >= 0; e = entries_[size_t(e)].next) consider(entries_[size_t(e)].face);
        }
  }
}

}  // namespace mr::surface_union
