#include "union/exact.h"

#include "union/crossing_doubles.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mutex>
#include <utility>

namespace mr::surface_union {

namespace {
// Lazy rationals of points shared by threads: a few locks, picked by address.
std::mutex& lock_of(const void* p) {
  static std::mutex locks[64];
  return locks[(reinterpret_cast<uintptr_t>(p) >> 4) % 64];
}
}  // namespace

QPoint::QPoint(const QPoint& o) : d(o.d), exact_double(o.exact_double) {
  if (o.q_.load(std::memory_order_acquire)) {
    o.q(0);  // canonical (and complete) before it is read
    q_.store(new std::array<mpq_class, 3>(*o.q_.load(std::memory_order_acquire)), std::memory_order_relaxed);
  } else if (o.recipe_) {
    recipe_ = new Recipe(*o.recipe_);
    canonical_.store(false, std::memory_order_relaxed);
  }
}

QPoint& QPoint::operator=(const QPoint& o) {
  if (this != &o) *this = QPoint(o);
  return *this;
}

const mpq_class& QPoint::q(int k) const {
  const auto* q = q_.load(std::memory_order_acquire);
  if (q && canonical_.load(std::memory_order_acquire)) return (*q)[k];
  return q_slow(k);
}

const mpq_class& QPoint::q_slow(int k) const {
  std::lock_guard<std::mutex> lock(lock_of(this));
  auto* q = build_locked();
  if (!canonical_.load(std::memory_order_acquire)) {
    for (auto& c : *q) c.canonicalize();
    canonical_.store(true, std::memory_order_release);
  }
  return (*q)[k];
}

namespace {
std::array<mpq_class, 3>* rationals_of(const QPoint::Recipe& recipe);
}  // namespace

std::array<mpq_class, 3>* QPoint::build_locked() const {
  auto* q = q_.load(std::memory_order_acquire);
  if (q) return q;
  q = recipe_ ? rationals_of(*recipe_) : new std::array<mpq_class, 3>{mpq_class(d[0]), mpq_class(d[1]), mpq_class(d[2])};
  q_.store(q, std::memory_order_release);
  return q;
}

const std::array<mpq_class, 3>* QPoint::built() const {
  if (const auto* q = q_.load(std::memory_order_acquire)) return q;
  std::lock_guard<std::mutex> lock(lock_of(this));
  return build_locked();
}

QPoint QPoint::lazy_crossing(const std::array<double, 3>& d, const Recipe& recipe) {
  QPoint r;
  r.d = d;
  r.recipe_ = new Recipe(recipe);
  r.canonical_.store(false, std::memory_order_relaxed);  // built unreduced
  return r;
}

QPoint make_point(const std::array<double, 3>& p) {
  QPoint r;
  r.d = p;  // exact: every double is a dyadic rational
  r.exact_double = true;
  return r;
}

QPoint make_point(const mpq_class& x, const mpq_class& y, const mpq_class& z) {
  mpq_class a(x), b(y), c(z);
  a.canonicalize();
  b.canonicalize();
  c.canonicalize();
  return make_point_canonical(std::move(a), std::move(b), std::move(c));
}

QPoint make_point_canonical(mpq_class&& x, mpq_class&& y, mpq_class&& z) {
  QPoint r;
  auto& q = r.own_q();
  q[0] = std::move(x);
  q[1] = std::move(y);
  q[2] = std::move(z);
  for (int k = 0; k < 3; ++k) r.d[k] = q[k].get_d();
  return r;
}

bool same_point(const QPoint& a, const QPoint& b) {
  // Truncation is monotone: different doubles, different rationals.
  if (a.d != b.d) return false;
  if (a.exact_double && b.exact_double) return true;
  return compare(a, b, 0) == 0 && compare(a, b, 1) == 0 && compare(a, b, 2) == 0;
}

mpq_class orient3d_exact(const double* a, const double* b, const double* c, const double* d) {
  mpq_class m[3][3];
  for (int k = 0; k < 3; ++k) {
    mpq_class ak(a[k]);
    m[0][k] = mpq_class(b[k]) - ak;
    m[1][k] = mpq_class(c[k]) - ak;
    m[2][k] = mpq_class(d[k]) - ak;
  }
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

namespace {

int scale_to_integers(const double* const* values, int n, mpz_class* out);
/// Exact sign of det[b-a, c-a, d-a] with integers (all inputs scaled to one power of two).
int orient3d_integer_sign(const double* a, const double* b, const double* c, const double* d);
/// The same for det[b-a, c-a] on axes (i, j).
int orient2d_integer_sign(const double* a, const double* b, const double* c, int i, int j);
/// The same for perpendicular_dot_sign.
int perpendicular_dot_integer_sign(const double* u, const double* w, const double* x, const double* y);

/// A point in homogeneous integers on two axes: (x / w, y / w).
struct Homogeneous2 {
  const mpz_class &x, &y, &w;
};
/// out = det[[x_u, y_u, w_u], [x_v, y_v, w_v], [x_p, y_p, w_p]] = w_u w_v w_p
/// orient2d(u, v, p); t is scratch.
void homogeneous_orient2d(mpz_class& out, mpz_class& t, Homogeneous2 u, Homogeneous2 v, Homogeneous2 p);
/// Sign of orient2d on rational points from their integers (QPoint::homogeneous): the
/// rationals' products and sums would each take a gcd.
int orient2d_homogeneous_sign(const QPoint& a, const QPoint& b, const QPoint& c, int i, int j);
/// The same for orient3d: the 4x4 determinant of the points' integers (x, y, z, w).
int orient3d_homogeneous_sign(const QPoint& a, const QPoint& b, const QPoint& c, const QPoint& d);

}  // namespace

int orient3d_unfiltered(const double* a, const double* b, const double* c, const double* d) {
  // Two equal points (a corner tested against its own face): zero without integers.
  auto same = [](const double* p, const double* q) { return p[0] == q[0] && p[1] == q[1] && p[2] == q[2]; };
  if (same(d, a) || same(d, b) || same(d, c) || same(a, b) || same(a, c) || same(b, c)) return 0;
  return orient3d_integer_sign(a, b, c, d);
}

int orient3d(const QPoint& a, const QPoint& b, const QPoint& c, const QPoint& d) {
  if (a.exact_double && b.exact_double && c.exact_double && d.exact_double)
    return orient3d(a.d.data(), b.d.data(), c.d.data(), d.d.data());
  double m[3][3];
  double mag = 0;
  for (int k = 0; k < 3; ++k) {
    m[0][k] = b.d[k] - a.d[k];
    m[1][k] = c.d[k] - a.d[k];
    m[2][k] = d.d[k] - a.d[k];
    mag = std::max({mag, std::fabs(a.d[k]), std::fabs(b.d[k]), std::fabs(c.d[k]), std::fabs(d.d[k])});
  }
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  // The doubles are within one ulp of the rationals (relative 2.2e-16 of |coordinate|):
  // each entry (a rounded difference) is off by at most e = 6.7e-16 mag. With M the
  // largest entry, each of the six products is then off by < 3 e M^2 + 3 e^2 M + e^3,
  // and evaluating in doubles adds < 7.8e-16 times the permanent (< 6 M^3). Twice that:
  // the bound follows the size of the tetrahedron, not its distance from the origin.
  double M = 0;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) M = std::max(M, std::fabs(m[r][k]));
  const double err = 6.7e-16 * mag;
  const double bound = 2 * (18 * err * M * M + 18 * err * err * M + 6 * err * err * err + 7.8e-16 * 6 * M * M * M);
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return orient3d_homogeneous_sign(a, b, c, d);
}

int perpendicular_dot_sign(const QPoint& u, const QPoint& w, const QPoint& x, const QPoint& y) {
  // (x-u).(y-u) |d|^2 - ((x-u).d)((y-u).d), d = w - u: |d|^2 times the perpendicular dot.
  {
    double d[3], a[3], b[3], mag = 0;
    for (int k = 0; k < 3; ++k) {
      d[k] = w.d[k] - u.d[k];
      a[k] = x.d[k] - u.d[k];
      b[k] = y.d[k] - u.d[k];
      mag = std::max({mag, std::fabs(u.d[k]), std::fabs(w.d[k]), std::fabs(x.d[k]), std::fabs(y.d[k])});
    }
    const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    const double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const double ad = a[0] * d[0] + a[1] * d[1] + a[2] * d[2];
    const double bd = b[0] * d[0] + b[1] * d[1] + b[2] * d[2];
    const double value = ab * dd - ad * bd;
    // Each coordinate difference is off by at most e1 = 6.7e-16 mag (both doubles
    // within one ulp, 2.2e-16 relative, of the rationals, plus the rounded subtraction),
    // a vector by e = sqrt(3) e1 < 1.2e-15 mag. A dot product x.y is then off by e (|x| + |y|) + e^2 plus its own
    // rounding (< 3.4e-16 |x| |y|); a product of two dots by the first times the other
    // dot and vice versa, plus rounding. The bound doubles that sum: generous, and it
    // scales with the features' size rather than with their distance from the origin.
    const double e = 1.2e-15 * mag;
    const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) * (1 + 1e-15);
    const double lb = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]) * (1 + 1e-15);
    const double ld = std::sqrt(dd) * (1 + 1e-15);
    auto dot_err = [&](double lx, double ly) { return e * (lx + ly) + e * e + 3.4e-16 * lx * ly; };
    const double e_ab = dot_err(la, lb), e_dd = dot_err(ld, ld), e_ad = dot_err(la, ld), e_bd = dot_err(lb, ld);
    const double m_ab = la * lb + e_ab, m_dd = ld * ld + e_dd, m_ad = la * ld + e_ad, m_bd = lb * ld + e_bd;
    const double err = m_ab * e_dd + m_dd * e_ab + m_ad * e_bd + m_bd * e_ad + 4.5e-16 * (m_ab * m_dd + m_ad * m_bd);
    const double bound = 2 * err;
    if (value > bound) return 1;
    if (value < -bound) return -1;
  }
  if (u.exact_double && w.exact_double && x.exact_double && y.exact_double)
    return perpendicular_dot_integer_sign(u.d.data(), w.d.data(), x.d.data(), y.d.data());
  mpq_class d[3], a[3], b[3];
  for (int k = 0; k < 3; ++k) {
    d[k] = w.q(k) - u.q(k);
    a[k] = x.q(k) - u.q(k);
    b[k] = y.q(k) - u.q(k);
  }
  const mpq_class dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const mpq_class ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const mpq_class ad = a[0] * d[0] + a[1] * d[1] + a[2] * d[2];
  const mpq_class bd = b[0] * d[0] + b[1] * d[1] + b[2] * d[2];
  return sgn(mpq_class(ab * dd - ad * bd));
}

mpq_class orient2d_exact(const QPoint& a, const QPoint& b, const QPoint& c, int i, int j) {
  return (b.q(i) - a.q(i)) * (c.q(j) - a.q(j)) - (b.q(j) - a.q(j)) * (c.q(i) - a.q(i));
}

int orient2d_unfiltered(const double* a, const double* b, const double* c, int i, int j) {
  // Collinear points on axis-parallel lines (common in CAD): exactly zero.
  if ((a[i] == b[i] && a[i] == c[i]) || (a[j] == b[j] && a[j] == c[j])) return 0;
  auto same = [&](const double* p, const double* q) { return p[i] == q[i] && p[j] == q[j]; };
  if (same(a, b) || same(a, c) || same(b, c)) return 0;
  return orient2d_integer_sign(a, b, c, i, j);
}

int orient2d_filter(const QPoint& a, const QPoint& b, const QPoint& c, int i, int j) {
  const double bx = b.d[i] - a.d[i], by = b.d[j] - a.d[j];
  const double cx = c.d[i] - a.d[i], cy = c.d[j] - a.d[j];
  const double l = bx * cy, r = by * cx;
  const double det = l - r;
  double bound;
  if (a.exact_double && b.exact_double && c.exact_double) {
    bound = 1e-15 * (std::fabs(l) + std::fabs(r));  // as orient2d on doubles
  } else {  // as orient2d on rational points
    const double m = std::max({std::fabs(a.d[i]), std::fabs(b.d[i]), std::fabs(c.d[i]), std::fabs(a.d[j]),
                               std::fabs(b.d[j]), std::fabs(c.d[j])});
    const double e = 6.7e-16 * m;
    bound = 2 * (e * (std::fabs(bx) + std::fabs(by) + std::fabs(cx) + std::fabs(cy)) + 2 * e * e +
                 3.3e-16 * (std::fabs(l) + std::fabs(r)));
  }
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return 2;
}

int orient2d(const QPoint& a, const QPoint& b, const QPoint& c, int i, int j) {
  if (a.exact_double && b.exact_double && c.exact_double) return orient2d(a.d.data(), b.d.data(), c.d.data(), i, j);
  const double bx = b.d[i] - a.d[i], by = b.d[j] - a.d[j];
  const double cx = c.d[i] - a.d[i], cy = c.d[j] - a.d[j];
  const double det = bx * cy - by * cx;
  // The doubles are within one ulp of the rationals: each difference is off by at most
  // e = 6.7e-16 m (m the largest coordinate), each product by e (|x| + |y|) + e^2, and
  // the evaluation adds < 3.3e-16 (|bx cy| + |by cx|). Twice that, so the bound follows
  // the triangle's size rather than its distance from the origin.
  const double m = std::max({std::fabs(a.d[i]), std::fabs(b.d[i]), std::fabs(c.d[i]), std::fabs(a.d[j]),
                             std::fabs(b.d[j]), std::fabs(c.d[j])});
  const double e = 6.7e-16 * m;
  const double bound = 2 * (e * (std::fabs(bx) + std::fabs(by) + std::fabs(cx) + std::fabs(cy)) + 2 * e * e +
                            3.3e-16 * (std::fabs(bx * cy) + std::fabs(by * cx)));
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return orient2d_homogeneous_sign(a, b, c, i, j);
}

namespace {

/// Integers m_i with values[i] = m_i * 2^e for one common exponent e (returned).
int scale_to_integers(const double* const* values, int n, mpz_class* out) {
  // Each nonzero double is an integer of at most 53 bits times 2^(ilogb - 52).
  int emin = std::numeric_limits<int>::max(), emax = std::numeric_limits<int>::min();
  for (int i = 0; i < n; ++i) {
    const double v = *values[i];
    if (v == 0) continue;
    const int e = std::ilogb(v) - 52;
    emin = std::min(emin, e);
    emax = std::max(emax, e);
  }
  if (emin == std::numeric_limits<int>::max()) emin = emax = 0;
  if (emax - emin > 900) {  // the scaled values would overflow a double: shift in GMP
    for (int i = 0; i < n; ++i) {
      const double v = *values[i];
      if (v == 0) { out[i] = 0; continue; }
      const int e = std::ilogb(v) - 52;
      mpz_set_d(out[i].get_mpz_t(), std::ldexp(v, -e));
      mpz_mul_2exp(out[i].get_mpz_t(), out[i].get_mpz_t(), e - emin);
    }
    return emin;
  }
  // Scaling by a power of two is exact, and mpz_set_d is exact on integral doubles.
  for (int i = 0; i < n; ++i) mpz_set_d(out[i].get_mpz_t(), std::ldexp(*values[i], -emin));
  return emin;
}

}  // namespace

namespace {

int orient3d_integer_sign(const double* a, const double* b, const double* c, const double* d) {
  const double* vals[12];
  for (int k = 0; k < 3; ++k) {
    vals[k] = &a[k];
    vals[3 + k] = &b[k];
    vals[6 + k] = &c[k];
    vals[9 + k] = &d[k];
  }
  // Reused across calls: GMP keeps the limbs, which saves most allocations.
  thread_local mpz_class z[12];
  thread_local mpz_class m[3][3];
  scale_to_integers(vals, 12, z);
  for (int k = 0; k < 3; ++k) {
    m[0][k] = z[3 + k] - z[k];
    m[1][k] = z[6 + k] - z[k];
    m[2][k] = z[9 + k] - z[k];
  }
  const mpz_class det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                        m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                        m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return sgn(det);
}

int orient2d_integer_sign(const double* a, const double* b, const double* c, int i, int j) {
  const double* vals[6] = {&a[i], &a[j], &b[i], &b[j], &c[i], &c[j]};
  thread_local mpz_class z[6];
  thread_local mpz_class m[4];
  scale_to_integers(vals, 6, z);
  m[0] = z[2] - z[0];
  m[1] = z[3] - z[1];
  m[2] = z[4] - z[0];
  m[3] = z[5] - z[1];
  const mpz_class det = m[0] * m[3] - m[1] * m[2];
  return sgn(det);
}

int perpendicular_dot_integer_sign(const double* u, const double* w, const double* x, const double* y) {
  const double* vals[12];
  for (int k = 0; k < 3; ++k) {
    vals[k] = &u[k];
    vals[3 + k] = &w[k];
    vals[6 + k] = &x[k];
    vals[9 + k] = &y[k];
  }
  thread_local mpz_class z[12];
  thread_local mpz_class d[3], a[3], b[3];
  scale_to_integers(vals, 12, z);
  for (int k = 0; k < 3; ++k) {
    d[k] = z[3 + k] - z[k];
    a[k] = z[6 + k] - z[k];
    b[k] = z[9 + k] - z[k];
  }
  const mpz_class dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const mpz_class ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const mpz_class ad = a[0] * d[0] + a[1] * d[1] + a[2] * d[2];
  const mpz_class bd = b[0] * d[0] + b[1] * d[1] + b[2] * d[2];
  return sgn(mpz_class(ab * dd - ad * bd));
}

void homogeneous_orient2d(mpz_class& out, mpz_class& t, Homogeneous2 u, Homogeneous2 v, Homogeneous2 p) {
  // Along the w column; fused multiply-adds, no temporaries.
  mpz_mul(t.get_mpz_t(), v.x.get_mpz_t(), p.y.get_mpz_t());
  mpz_submul(t.get_mpz_t(), v.y.get_mpz_t(), p.x.get_mpz_t());
  mpz_mul(out.get_mpz_t(), u.w.get_mpz_t(), t.get_mpz_t());
  mpz_mul(t.get_mpz_t(), u.x.get_mpz_t(), p.y.get_mpz_t());
  mpz_submul(t.get_mpz_t(), u.y.get_mpz_t(), p.x.get_mpz_t());
  mpz_submul(out.get_mpz_t(), v.w.get_mpz_t(), t.get_mpz_t());
  mpz_mul(t.get_mpz_t(), u.x.get_mpz_t(), v.y.get_mpz_t());
  mpz_submul(t.get_mpz_t(), u.y.get_mpz_t(), v.x.get_mpz_t());
  mpz_addmul(out.get_mpz_t(), p.w.get_mpz_t(), t.get_mpz_t());
}

int orient2d_homogeneous_sign(const QPoint& a, const QPoint& b, const QPoint& c, int i, int j) {
  thread_local mpz_class n[3][2], w[3], det, t;  // reused across calls (saves allocations)
  const int axes[2] = {i, j};
  a.homogeneous(axes, 2, n[0], w[0]);
  b.homogeneous(axes, 2, n[1], w[1]);
  c.homogeneous(axes, 2, n[2], w[2]);
  homogeneous_orient2d(det, t, {n[0][0], n[0][1], w[0]}, {n[1][0], n[1][1], w[1]}, {n[2][0], n[2][1], w[2]});
  return sgn(det);  // every w is positive
}

int orient3d_homogeneous_sign(const QPoint& a, const QPoint& b, const QPoint& c, const QPoint& d) {
  thread_local mpz_class n[4][4], s[6], r[6], det;  // reused across calls (saves allocations)
  const int xyz[3] = {0, 1, 2};
  const QPoint* p[4] = {&a, &b, &c, &d};
  for (int m = 0; m < 4; ++m) p[m]->homogeneous(xyz, 3, n[m], n[m][3]);
  // Laplace along the first two rows: their 2x2 minors times the complementary minors
  // of the last two, columns (x, y, z, w) paired as (01, 02, 03, 12, 13, 23).
  const int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (int q = 0; q < 6; ++q) {
    const int u = pairs[q][0], v = pairs[q][1];
    mpz_mul(s[q].get_mpz_t(), n[0][u].get_mpz_t(), n[1][v].get_mpz_t());
    mpz_submul(s[q].get_mpz_t(), n[0][v].get_mpz_t(), n[1][u].get_mpz_t());
    mpz_mul(r[q].get_mpz_t(), n[2][u].get_mpz_t(), n[3][v].get_mpz_t());
    mpz_submul(r[q].get_mpz_t(), n[2][v].get_mpz_t(), n[3][u].get_mpz_t());
  }
  // det = s01 r23 - s02 r13 + s03 r12 + s12 r03 - s13 r02 + s23 r01.
  mpz_mul(det.get_mpz_t(), s[0].get_mpz_t(), r[5].get_mpz_t());
  mpz_submul(det.get_mpz_t(), s[1].get_mpz_t(), r[4].get_mpz_t());
  mpz_addmul(det.get_mpz_t(), s[2].get_mpz_t(), r[3].get_mpz_t());
  mpz_addmul(det.get_mpz_t(), s[3].get_mpz_t(), r[2].get_mpz_t());
  mpz_submul(det.get_mpz_t(), s[4].get_mpz_t(), r[1].get_mpz_t());
  mpz_addmul(det.get_mpz_t(), s[5].get_mpz_t(), r[0].get_mpz_t());
  // With every w positive, det = -w_a w_b w_c w_d orient3d (subtract the first row from
  // the others, expand along the w column).
  return -sgn(det);
}

}  // namespace

void QPoint::homogeneous(const int* axes, int count, mpz_class* n, mpz_class& w) const {
  const auto* q = exact_double || !recipe_ ? q_.load(std::memory_order_acquire) : built();
  if (exact_double || !q) {  // the doubles are the rationals: integers times 2^e
    const double* vals[3];
    for (int m = 0; m < count; ++m) vals[m] = &d[axes[m]];
    const int e = scale_to_integers(vals, count, n);
    w = 1;
    if (e < 0) mpz_mul_2exp(w.get_mpz_t(), w.get_mpz_t(), -e);
    for (int m = 0; m < count && e > 0; ++m) mpz_mul_2exp(n[m].get_mpz_t(), n[m].get_mpz_t(), e);
    return;
  }
  // A canonical form never changes again; an unreduced one may be put in canonical
  // form in place by another thread (q_slow): read it under the same lock.
  std::unique_lock<std::mutex> lock(lock_of(this), std::defer_lock);
  if (!canonical_.load(std::memory_order_acquire)) lock.lock();
  // The product of the denominators (all positive), each distinct one taken once: an
  // unreduced point has one for all its coordinates.
  mpz_set(n[0].get_mpz_t(), (*q)[axes[0]].get_num_mpz_t());
  mpz_set(w.get_mpz_t(), (*q)[axes[0]].get_den_mpz_t());
  for (int m = 1; m < count; ++m) {
    mpz_srcptr num = (*q)[axes[m]].get_num_mpz_t(), den = (*q)[axes[m]].get_den_mpz_t();
    if (mpz_cmp(den, w.get_mpz_t()) == 0) {
      mpz_set(n[m].get_mpz_t(), num);
      continue;
    }
    for (int l = 0; l < m; ++l) mpz_mul(n[l].get_mpz_t(), n[l].get_mpz_t(), den);
    mpz_mul(n[m].get_mpz_t(), num, w.get_mpz_t());
    mpz_mul(w.get_mpz_t(), w.get_mpz_t(), den);
  }
}

namespace {

/// The integers a crossing is made of, all inputs scaled by one power of two: a and b
/// (A, B), their sides oa and ob of the plane or the line, the exponent e.
struct CrossingIntegers {
  const mpz_class *A, *B;
  mpz_class *oa, *ob;
  int e;
};

/// For Recipe::kEdgePlane: v = a, b, f0, f1, f2. Scratch of this thread, valid until the next call.
CrossingIntegers edge_plane_integers(const double* v) {
  const double* vals[15];
  for (int m = 0; m < 15; ++m) vals[m] = &v[m];
  thread_local mpz_class z[15];  // reused across calls (saves allocations)
  thread_local mpz_class u[3], w[3], ra[3], rb[3], n[3], oa, ob;
  const int e = scale_to_integers(vals, 15, z);
  const mpz_class *A = z, *B = z + 3, *F0 = z + 6, *F1 = z + 9, *F2 = z + 12;
  for (int k = 0; k < 3; ++k) {
    u[k] = F1[k] - F0[k];
    w[k] = F2[k] - F0[k];
    ra[k] = A[k] - F0[k];
    rb[k] = B[k] - F0[k];
  }
  // n = u x w and the two sides, with fused multiply-adds (no temporaries).
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    mpz_mul(n[k].get_mpz_t(), u[i].get_mpz_t(), w[j].get_mpz_t());
    mpz_submul(n[k].get_mpz_t(), u[j].get_mpz_t(), w[i].get_mpz_t());
  }
  mpz_mul(oa.get_mpz_t(), n[0].get_mpz_t(), ra[0].get_mpz_t());
  mpz_mul(ob.get_mpz_t(), n[0].get_mpz_t(), rb[0].get_mpz_t());
  for (int k = 1; k < 3; ++k) {
    mpz_addmul(oa.get_mpz_t(), n[k].get_mpz_t(), ra[k].get_mpz_t());
    mpz_addmul(ob.get_mpz_t(), n[k].get_mpz_t(), rb[k].get_mpz_t());
  }
  return {A, B, &oa, &ob, e};
}

/// For Recipe::kSegmentLine: v = a, b, c0_i, c0_j, c1_i, c1_j. Scratch as above.
CrossingIntegers segment_line_integers(const double* v, int i, int j) {
  const double* vals[10];
  for (int m = 0; m < 10; ++m) vals[m] = &v[m];
  thread_local mpz_class z[10];
  thread_local mpz_class ux, uy, oa, ob;
  const int e = scale_to_integers(vals, 10, z);
  const mpz_class *A = z, *B = z + 3;
  ux = z[8] - z[6];
  uy = z[9] - z[7];
  // orient2d(c0, c1, x) = ux (x_j - c0_j) - uy (x_i - c0_i)
  oa = ux * (A[j] - z[7]) - uy * (A[i] - z[6]);
  ob = ux * (B[j] - z[7]) - uy * (B[i] - z[6]);
  return {A, B, &oa, &ob, e};
}

CrossingIntegers integers_of(const QPoint::Recipe& recipe) {
  return recipe.kind == QPoint::Recipe::kEdgePlane ? edge_plane_integers(recipe.v)
                                                   : segment_line_integers(recipe.v, recipe.i, recipe.j);
}

/// x = (oa B - ob A) / (oa - ob) 2^e, unreduced, with one positive denominator (the gcd
/// is the expensive part, and most crossings are never needed exactly). Flips the signs
/// of oa and ob where the denominator needs it.
void crossing_rationals(const CrossingIntegers& c, std::array<mpq_class, 3>& x) {
  mpz_class &oa = *c.oa, &ob = *c.ob;
  thread_local mpz_class den;
  mpz_sub(den.get_mpz_t(), oa.get_mpz_t(), ob.get_mpz_t());
  if (sgn(den) < 0) {  // a positive denominator: the truncated doubles need no canonical form
    mpz_neg(den.get_mpz_t(), den.get_mpz_t());
    mpz_neg(oa.get_mpz_t(), oa.get_mpz_t());
    mpz_neg(ob.get_mpz_t(), ob.get_mpz_t());
  }
  if (c.e < 0) mpz_mul_2exp(den.get_mpz_t(), den.get_mpz_t(), -c.e);  // once for the three coordinates
  for (int k = 0; k < 3; ++k) {
    mpz_ptr num = x[size_t(k)].get_num_mpz_t();
    mpz_mul(num, oa.get_mpz_t(), c.B[k].get_mpz_t());  // no temporaries
    mpz_submul(num, ob.get_mpz_t(), c.A[k].get_mpz_t());
    if (c.e > 0) mpz_mul_2exp(num, num, c.e);
    mpz_set(x[size_t(k)].get_den_mpz_t(), den.get_mpz_t());
  }
}

std::array<mpq_class, 3>* rationals_of(const QPoint::Recipe& recipe) {
  auto* x = new std::array<mpq_class, 3>();
  crossing_rationals(integers_of(recipe), *x);
  return x;
}

/// A crossing's doubles (its rationals truncated), without keeping the rationals.
std::array<double, 3> truncated_crossing(const QPoint::Recipe& recipe);

}  // namespace

QPoint edge_plane_crossing(const double* a, const double* b, const double* f0, const double* f1, const double* f2) {
  // CAD: an edge along a coordinate axis crosses a plane across that axis where the
  // edge's two fixed coordinates meet the plane's: the point is three doubles.
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    if (f0[k] == f1[k] && f0[k] == f2[k] && a[i] == b[i] && a[j] == b[j]) {
      std::array<double, 3> p{a[0], a[1], a[2]};
      p[k] = f0[k];
      return make_point(p);
    }
  }
  QPoint::Recipe recipe{QPoint::Recipe::kEdgePlane, 0, 0, {}};
  for (int k = 0; k < 3; ++k) {
    recipe.v[k] = a[k];
    recipe.v[3 + k] = b[k];
    recipe.v[6 + k] = f0[k];
    recipe.v[9 + k] = f1[k];
    recipe.v[12 + k] = f2[k];
  }
  return QPoint::lazy_crossing(truncated_crossing(recipe), recipe);
}

QPoint segment_line_crossing(const double* a, const double* b, const double* c0, const double* c1, int i, int j) {
  // CAD: a segment along axis i (or j) in a plane across the third axis k crosses a line
  // along the other axis where their fixed coordinates meet: the point is three doubles.
  const int k = 3 - i - j;
  if (a[k] == b[k]) {
    std::array<double, 3> p{a[0], a[1], a[2]};
    if (a[i] == b[i] && c0[j] == c1[j]) {
      p[j] = c0[j];
      return make_point(p);
    }
    if (a[j] == b[j] && c0[i] == c1[i]) {
      p[i] = c0[i];
      return make_point(p);
    }
  }
  QPoint::Recipe recipe{QPoint::Recipe::kSegmentLine, static_cast<signed char>(i), static_cast<signed char>(j),
                        {a[0], a[1], a[2], b[0], b[1], b[2], c0[i], c0[j], c1[i], c1[j]}};
  return QPoint::lazy_crossing(truncated_crossing(recipe), recipe);
}

namespace {

std::array<double, 3> truncated_crossing(const QPoint::Recipe& recipe) {
  std::array<double, 3> d;
  if (truncated_crossing_on_stack(recipe, d)) return d;
  thread_local std::array<mpq_class, 3> x;  // reused: no allocation per crossing
  crossing_rationals(integers_of(recipe), x);
  return {x[0].get_d(), x[1].get_d(), x[2].get_d()};
}

}  // namespace

QPoint segment_line_crossing(const QPoint& a, const QPoint& b, const QPoint& c, const QPoint& d, int i, int j) {
  thread_local mpz_class A[3], B[3], wa, wb, C[2], D[2], wc, wd, ha, hb, t, den;
  const int xyz[3] = {0, 1, 2}, axes[2] = {i, j};
  a.homogeneous(xyz, 3, A, wa);
  b.homogeneous(xyz, 3, B, wb);
  c.homogeneous(axes, 2, C, wc);
  d.homogeneous(axes, 2, D, wd);
  // ha = wc wd wa orient2d(c, d, a), hb the same for b. The crossing a + t (b - a),
  // t = oa / (oa - ob) with oa, ob the orient2d values, is then (ha B - hb A) / (ha wb - hb wa).
  homogeneous_orient2d(ha, t, {C[0], C[1], wc}, {D[0], D[1], wd}, {A[i], A[j], wa});
  homogeneous_orient2d(hb, t, {C[0], C[1], wc}, {D[0], D[1], wd}, {B[i], B[j], wb});
  mpz_mul(den.get_mpz_t(), ha.get_mpz_t(), wb.get_mpz_t());
  mpz_submul(den.get_mpz_t(), hb.get_mpz_t(), wa.get_mpz_t());
  if (sgn(den) < 0) {  // a positive denominator, as crossing_rationals
    mpz_neg(den.get_mpz_t(), den.get_mpz_t());
    mpz_neg(ha.get_mpz_t(), ha.get_mpz_t());
    mpz_neg(hb.get_mpz_t(), hb.get_mpz_t());
  }
  QPoint r;
  auto& q = r.own_q();
  for (int k = 0; k < 3; ++k) {
    mpq_class& x = q[k];
    mpz_mul(x.get_num_mpz_t(), ha.get_mpz_t(), B[k].get_mpz_t());
    mpz_submul(x.get_num_mpz_t(), hb.get_mpz_t(), A[k].get_mpz_t());
    mpz_set(x.get_den_mpz_t(), den.get_mpz_t());
    r.d[k] = x.get_d();
  }
  r.canonical_ = false;
  return r;
}

QPoint lerp(const QPoint& a, const QPoint& b, const mpq_class& t) {
  return make_point_canonical(a.q(0) + t * (b.q(0) - a.q(0)), a.q(1) + t * (b.q(1) - a.q(1)), a.q(2) + t * (b.q(2) - a.q(2)));
}

Projection face_projection(const QPoint& qa, const QPoint& qb, const QPoint& qc) {
  const double* a = qa.d.data();
  const double* b = qb.d.data();
  const double* c = qc.d.data();
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  int k = 0;
  for (int t = 1; t < 3; ++t)
    if (std::fabs(n[t]) > std::fabs(n[k])) k = t;
  Projection p{(k + 1) % 3, (k + 2) % 3};
  int o = orient2d(qa, qb, qc, p.i, p.j);
  for (int t = 0; t < 3 && o == 0; ++t) {  // the double normal chose a degenerate axis
    p = {(t + 1) % 3, (t + 2) % 3};
    o = orient2d(qa, qb, qc, p.i, p.j);
  }
  if (o < 0) std::swap(p.i, p.j);
  return p;
}

int compare(const QPoint& a, const QPoint& b, int axis) {
  // The doubles are the rationals truncated towards zero, a monotone map: different doubles decide.
  if (a.d[axis] < b.d[axis]) return -1;
  if (a.d[axis] > b.d[axis]) return 1;
  if (a.exact_double && b.exact_double) return 0;
  // n_a / w_a against n_b / w_b with positive w: cross-multiplied, no canonical forms.
  thread_local mpz_class na, wa, nb, wb;
  a.homogeneous(&axis, 1, &na, wa);
  b.homogeneous(&axis, 1, &nb, wb);
  if (mpz_cmp(wa.get_mpz_t(), wb.get_mpz_t()) != 0) {
    mpz_mul(na.get_mpz_t(), na.get_mpz_t(), wb.get_mpz_t());
    mpz_mul(nb.get_mpz_t(), nb.get_mpz_t(), wa.get_mpz_t());
  }
  const int c = mpz_cmp(na.get_mpz_t(), nb.get_mpz_t());
  return (c > 0) - (c < 0);
}

}  // namespace mr::surface_union
