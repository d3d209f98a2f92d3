// Exact geometry for the union: points with rational coordinates (GMP) and
// orientation predicates that first try a floating-point filter and fall back to
// exact rational arithmetic, so no tolerance ever decides a topological question.
#pragma once

#include <gmpxx.h>

#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <utility>

namespace mr::surface_union {

/// A point with exact rational coordinates and their truncated (towards zero) double
/// approximation (the same rational always gives the same doubles, and different
/// doubles mean different rationals). The rationals are built on first use: input
/// vertices are doubles and most predicates are decided by filters on the doubles.
class QPoint {
public:
  std::array<double, 3> d;
  /// The doubles are the rationals exactly (input vertices): predicates on such points
  /// run on the doubles with an integer fallback and build no rationals.
  bool exact_double = false;

  /// The doubles a crossing was computed from: its rationals are built from them only
  /// when a predicate needs them (most crossings are decided on their doubles alone).
  struct Recipe {
    enum Kind : signed char { kEdgePlane, kSegmentLine } kind;
    signed char i, j;  // kSegmentLine: the projection's axes
    double v[15];      // kEdgePlane: a, b, f0, f1, f2; kSegmentLine: a, b, c0_i, c0_j, c1_i, c1_j
  };

  QPoint() = default;
  ~QPoint() {
    delete q_.load(std::memory_order_relaxed);
    delete recipe_;
  }
  QPoint(const QPoint& o);
  QPoint& operator=(const QPoint& o);
  QPoint(QPoint&& o) noexcept
      : d(o.d), exact_double(o.exact_double), q_(o.q_.exchange(nullptr, std::memory_order_relaxed)),
        canonical_(o.canonical_.load(std::memory_order_relaxed)), recipe_(std::exchange(o.recipe_, nullptr)) {}
  QPoint& operator=(QPoint&& o) noexcept {
    if (this != &o) {
      d = o.d;
      exact_double = o.exact_double;
      delete q_.exchange(o.q_.exchange(nullptr, std::memory_order_relaxed), std::memory_order_relaxed);
      canonical_.store(o.canonical_.load(std::memory_order_relaxed), std::memory_order_relaxed);
      delete recipe_;
      recipe_ = std::exchange(o.recipe_, nullptr);
    }
    return *this;
  }

  /// Exact coordinate k (canonical).
  const mpq_class& q(int k) const;
  /// Integers n[0..count) and w > 0 with coordinate axes[m] = n[m] / w, exactly, taken
  /// from the stored form as it is: no gcd, which is what canonical forms cost.
  void homogeneous(const int* axes, int count, mpz_class* n, mpz_class& w) const;

private:
  friend QPoint make_point(const std::array<double, 3>& p);
  friend QPoint make_point(const mpq_class& x, const mpq_class& y, const mpq_class& z);
  friend QPoint make_point_canonical(mpq_class&& x, mpq_class&& y, mpq_class&& z);
  friend QPoint edge_plane_crossing(const double*, const double*, const double*, const double*, const double*);
  friend QPoint segment_line_crossing(const double*, const double*, const double*, const double*, int, int);
  friend QPoint segment_line_crossing(const QPoint&, const QPoint&, const QPoint&, const QPoint&, int, int);
  /// A crossing with these doubles, its rationals to be built from `recipe`.
  static QPoint lazy_crossing(const std::array<double, 3>& d, const Recipe& recipe);
  // Built or put in canonical form on first use, possibly by several threads reading
  // the same point at once: the first one does it under a lock and publishes it.
  const mpq_class& q_slow(int k) const;
  std::array<mpq_class, 3>& own_q() {
    if (!q_.load(std::memory_order_relaxed)) q_.store(new std::array<mpq_class, 3>(), std::memory_order_relaxed);
    return *q_.load(std::memory_order_relaxed);
  }
  /// The rationals, built from recipe_ (or from the doubles) if they are not yet: the
  /// lock of this point held.
  std::array<mpq_class, 3>* build_locked() const;
  /// The same, taking the lock when they have to be built.
  const std::array<mpq_class, 3>* built() const;
  mutable std::atomic<std::array<mpq_class, 3>*> q_{nullptr};
  // false: the rationals are unreduced, with one positive denominator (crossings).
  mutable std::atomic<bool> canonical_{true};
  const Recipe* recipe_ = nullptr;  // owned; null unless a crossing
};

QPoint make_point(const std::array<double, 3>& p);
QPoint make_point(const mpq_class& x, const mpq_class& y, const mpq_class& z);
/// The same for coordinates already in canonical form (results of rational arithmetic).
QPoint make_point_canonical(mpq_class&& x, mpq_class&& y, mpq_class&& z);
bool same_point(const QPoint& a, const QPoint& b);

/// orient3d below where its floating-point filter cannot decide: exact (equal points,
/// integers).
int orient3d_unfiltered(const double* a, const double* b, const double* c, const double* d);

/// Sign of the signed volume of tetrahedron (a,b,c,d) for double inputs: +1 when d
/// lies on the side of plane (a,b,c) its normal (b-a)x(c-a) points away from... i.e.
/// the sign of det[b-a, c-a, d-a]. Exact. The filter is inline, as orient2d's below:
/// the clearance checks call it for every face pair they cannot separate otherwise.
inline int orient3d(const double* a, const double* b, const double* c, const double* d) {
  // Points on one axis-aligned plane (common in CAD models): exactly coplanar.
  for (int k = 0; k < 3; ++k)
    if (a[k] == b[k] && a[k] == c[k] && a[k] == d[k]) return 0;
  const double bx = b[0] - a[0], by = b[1] - a[1], bz = b[2] - a[2];
  const double cx = c[0] - a[0], cy = c[1] - a[1], cz = c[2] - a[2];
  const double dx = d[0] - a[0], dy = d[1] - a[1], dz = d[2] - a[2];
  const double t1 = cy * dz, t2 = cz * dy, t3 = cx * dz, t4 = cz * dx, t5 = cx * dy, t6 = cy * dx;
  const double det = bx * (t1 - t2) - by * (t3 - t4) + bz * (t5 - t6);
  const double perm = std::fabs(bx) * (std::fabs(t1) + std::fabs(t2)) + std::fabs(by) * (std::fabs(t3) + std::fabs(t4)) +
                      std::fabs(bz) * (std::fabs(t5) + std::fabs(t6));
  // Shewchuk's bound for this evaluation order is 7.8e-16 * perm; the differences
  // themselves are rounded too, so we use a generous 1e-14 (the fallback is exact).
  const double bound = 1e-14 * perm;
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return orient3d_unfiltered(a, b, c, d);
}

/// orient2d below where its floating-point filter cannot decide: exact (integers).
int orient2d_unfiltered(const double* a, const double* b, const double* c, int i, int j);

/// Sign of det[b-a, c-a] of the projections of double points on axes (i, j). Exact.
/// The filter is inline: the clearance checks and the re-triangulation call this
/// about a million times on a CAD model, and the filter decides nearly all of them.
inline int orient2d(const double* a, const double* b, const double* c, int i, int j) {
  const double bx = b[i] - a[i], by = b[j] - a[j];
  const double cx = c[i] - a[i], cy = c[j] - a[j];
  const double l = bx * cy, r = by * cx;
  const double det = l - r;
  // Shewchuk's bound for this evaluation is 3.3e-16 (|l| + |r|); 1e-15 is generous.
  const double bound = 1e-15 * (std::fabs(l) + std::fabs(r));
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return orient2d_unfiltered(a, b, c, i, j);
}

/// Sign of det[b-a, c-a, d-a] for rational points (filter on the doubles, exact fallback).
int orient3d(const QPoint& a, const QPoint& b, const QPoint& c, const QPoint& d);

/// Sign of the dot product of the parts of (x - u) and (y - u) perpendicular to (w - u). Exact.
int perpendicular_dot_sign(const QPoint& u, const QPoint& w, const QPoint& x, const QPoint& y);

/// det[b-a, c-a, d-a] exactly.
mpq_class orient3d_exact(const double* a, const double* b, const double* c, const double* d);

/// Sign of det[b-a, c-a] of the projections of a, b, c on axes (i, j). Exact.
int orient2d(const QPoint& a, const QPoint& b, const QPoint& c, int i, int j);

/// Sign of det[b-a, c-a] on axes (i, j) where the floating-point filter of orient2d
/// decides it, else 2 (no exact arithmetic).
int orient2d_filter(const QPoint& a, const QPoint& b, const QPoint& c, int i, int j);

/// det[b-a, c-a] on axes (i, j), exactly (rational arithmetic: orient2d above gets the
/// sign from integers).
mpq_class orient2d_exact(const QPoint& a, const QPoint& b, const QPoint& c, int i, int j);

/// The point where segment (a, b) crosses the plane of (f0, f1, f2), exactly; a and b
/// must lie strictly on opposite sides. Its doubles are computed with integers (all
/// inputs scaled to one power of two, crossing_doubles.h); its rationals, unreduced, only
/// when first needed. An edge along an axis crossing a plane across it gives a point of
/// doubles (exact_double), no integers.
QPoint edge_plane_crossing(const double* a, const double* b, const double* f0, const double* f1, const double* f2);

/// The point where segment (a, b) crosses the line (c0, c1) in the projection on axes
/// (i, j), exactly; a and b must not both lie on the line. Integers as above; a segment
/// and a line along the two axes of a plane across the third give a point of doubles.
QPoint segment_line_crossing(const double* a, const double* b, const double* c0, const double* c1, int i, int j);

/// The same for rational points: where segment (a, b) crosses line (c, d) in the
/// projection on axes (i, j); a and b must lie strictly on opposite sides of the line.
/// Computed from the points' integers (QPoint::homogeneous), left unreduced.
QPoint segment_line_crossing(const QPoint& a, const QPoint& b, const QPoint& c, const QPoint& d, int i, int j);

/// a + t (b - a), exactly.
QPoint lerp(const QPoint& a, const QPoint& b, const mpq_class& t);

/// Two axes (i, j) on which triangle (a, b, c) projects without degenerating and
/// counter-clockwise (orient2d > 0): the plane of a face in 2D.
struct Projection {
  int i, j;
};
Projection face_projection(const QPoint& a, const QPoint& b, const QPoint& c);

/// Exact comparison of coordinate `axis`: -1, 0, +1.
int compare(const QPoint& a, const QPoint& b, int axis);

}  // namespace mr::surface_union
