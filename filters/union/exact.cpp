#include "union/exact.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace mr::surface_union {

namespace {

int sign_of(const mpq_class& v) { return sgn(v); }

}  // namespace

QPoint make_point(const std::array<double, 3>& p) {
  QPoint r;
  for (int k = 0; k < 3; ++k) {
    r.q[k] = p[k];  // exact: every double is a dyadic rational
    r.d[k] = p[k];
  }
  return r;
}

QPoint make_point(const mpq_class& x, const mpq_class& y, const mpq_class& z) {
  QPoint r;
  r.q = {x, y, z};
  for (int k = 0; k < 3; ++k) {
    r.q[k].canonicalize();
    r.d[k] = r.q[k].get_d();
  }
  return r;
}

bool same_point(const QPoint& a, const QPoint& b) {
  return a.q[0] == b.q[0] && a.q[1] == b.q[1] && a.q[2] == b.q[2];
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

/// Exact sign of det[b-a, c-a, d-a] with integers (all inputs scaled to one power of two).
int orient3d_integer_sign(const double* a, const double* b, const double* c, const double* d);

}  // namespace

int orient3d(const double* a, const double* b, const double* c, const double* d) {
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
  return orient3d_integer_sign(a, b, c, d);
}

int orient3d(const QPoint& a, const QPoint& b, const QPoint& c, const QPoint& d) {
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
  // each entry is off by at most ~4.4e-16 mag, so the determinant by at most
  // 6 * 3 * 4.4e-16 * mag * (2 mag)^2 < 3.2e-14 mag^3; 1e-13 is generous.
  const double bound = 1e-13 * mag * mag * mag;
  if (det > bound) return 1;
  if (det < -bound) return -1;
  mpq_class q[3][3];
  for (int k = 0; k < 3; ++k) {
    q[0][k] = b.q[k] - a.q[k];
    q[1][k] = c.q[k] - a.q[k];
    q[2][k] = d.q[k] - a.q[k];
  }
  const mpq_class e = q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) - q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0]) +
                      q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
  return sgn(e);
}

int perpendicular_dot_sign(const QPoint& u, const QPoint& w, const QPoint& x, const QPoint& y) {
  // (x-u).(y-u) |d|^2 - ((x-u).d)((y-u).d), d = w - u: |d|^2 times the perpendicular dot.
  mpq_class d[3], a[3], b[3];
  for (int k = 0; k < 3; ++k) {
    d[k] = w.q[k] - u.q[k];
    a[k] = x.q[k] - u.q[k];
    b[k] = y.q[k] - u.q[k];
  }
  const mpq_class dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const mpq_class ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const mpq_class ad = a[0] * d[0] + a[1] * d[1] + a[2] * d[2];
  const mpq_class bd = b[0] * d[0] + b[1] * d[1] + b[2] * d[2];
  return sgn(mpq_class(ab * dd - ad * bd));
}

mpq_class orient2d_exact(const QPoint& a, const QPoint& b, const QPoint& c, int i, int j) {
  return (b.q[i] - a.q[i]) * (c.q[j] - a.q[j]) - (b.q[j] - a.q[j]) * (c.q[i] - a.q[i]);
}

int orient2d(const QPoint& a, const QPoint& b, const QPoint& c, int i, int j) {
  const double bx = b.d[i] - a.d[i], by = b.d[j] - a.d[j];
  const double cx = c.d[i] - a.d[i], cy = c.d[j] - a.d[j];
  const double det = bx * cy - by * cx;
  // The doubles are within one ulp of the rationals: bound the error by the
  // magnitudes of the coordinates involved, generously.
  const double mi = std::fabs(a.d[i]) + std::fabs(b.d[i]) + std::fabs(c.d[i]);
  const double mj = std::fabs(a.d[j]) + std::fabs(b.d[j]) + std::fabs(c.d[j]);
  const double bound = 1e-13 * mi * mj;
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return sign_of(orient2d_exact(a, b, c, i, j));
}

namespace {

/// Integers m_i with values[i] = m_i * 2^e for one common exponent e (returned).
int scale_to_integers(const double* const* values, int n, mpz_class* out) {
  int emin = std::numeric_limits<int>::max();
  std::int64_t mant[16];
  int expo[16];
  for (int i = 0; i < n; ++i) {
    const double v = *values[i];
    if (v == 0) { mant[i] = 0; expo[i] = 0; continue; }
    int e;
    const double f = std::frexp(v, &e);  // v = f 2^e, 0.5 <= |f| < 1
    mant[i] = std::int64_t(std::ldexp(f, 53));
    expo[i] = e - 53;
    emin = std::min(emin, expo[i]);
  }
  if (emin == std::numeric_limits<int>::max()) emin = 0;
  for (int i = 0; i < n; ++i) {
    out[i] = static_cast<long>(mant[i]);
    if (mant[i] != 0) mpz_mul_2exp(out[i].get_mpz_t(), out[i].get_mpz_t(), expo[i] - emin);
  }
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

}  // namespace

QPoint edge_plane_crossing(const double* a, const double* b, const double* f0, const double* f1, const double* f2) {
  const double* vals[15];
  for (int k = 0; k < 3; ++k) {
    vals[k] = &a[k];
    vals[3 + k] = &b[k];
    vals[6 + k] = &f0[k];
    vals[9 + k] = &f1[k];
    vals[12 + k] = &f2[k];
  }
  thread_local mpz_class z[15];  // reused across calls (saves allocations)
  thread_local mpz_class u[3], v[3], ra[3], rb[3];
  const int e = scale_to_integers(vals, 15, z);
  const mpz_class *A = z, *B = z + 3, *F0 = z + 6, *F1 = z + 9, *F2 = z + 12;
  for (int k = 0; k < 3; ++k) {
    u[k] = F1[k] - F0[k];
    v[k] = F2[k] - F0[k];
    ra[k] = A[k] - F0[k];
    rb[k] = B[k] - F0[k];
  }
  const mpz_class n0 = u[1] * v[2] - u[2] * v[1], n1 = u[2] * v[0] - u[0] * v[2], n2 = u[0] * v[1] - u[1] * v[0];
  const mpz_class oa = n0 * ra[0] + n1 * ra[1] + n2 * ra[2];
  const mpz_class ob = n0 * rb[0] + n1 * rb[1] + n2 * rb[2];
  mpz_class den = oa - ob;
  mpq_class c[3];
  for (int k = 0; k < 3; ++k) {
    mpz_class num = oa * B[k] - ob * A[k];
    mpz_class d = den;
    if (e >= 0) num <<= e;
    else d <<= -e;
    c[k] = mpq_class(num, d);
  }
  return make_point(c[0], c[1], c[2]);  // canonicalizes
}

QPoint lerp(const QPoint& a, const QPoint& b, const mpq_class& t) {
  return make_point(a.q[0] + t * (b.q[0] - a.q[0]), a.q[1] + t * (b.q[1] - a.q[1]), a.q[2] + t * (b.q[2] - a.q[2]));
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
  return cmp(a.q[axis], b.q[axis]);
}

}  // namespace mr::surface_union
