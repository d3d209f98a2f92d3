// The doubles of crossing points from stack integers, checked against rational
// arithmetic done here, independently of the library's integer code.
#include "union/crossing_doubles.h"
#include "union/exact.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace mr::surface_union;

namespace {

mpq_class Q(double x) { return mpq_class(x); }

/// a + t (b - a) on coordinate k, t where the side values oa and ob give it, truncated.
double truncated(const mpq_class& oa, const mpq_class& ob, const double* a, const double* b, int k) {
  const mpq_class t = oa / (oa - ob);
  const mpq_class x = Q(a[k]) + t * (Q(b[k]) - Q(a[k]));
  return x.get_d();  // GMP truncates towards zero
}

/// Coordinates in [-2, 2] whose exponents spread over up to `binades` (0: uniform).
struct Coordinates {
  std::mt19937_64 rng;
  int binades;
  double operator()() {
    std::uniform_real_distribution<double> u(-2, 2);
    double x = u(rng);
    if (binades > 0) x = std::ldexp(x, -int(rng() % uint64_t(binades)));
    if (rng() % 16 == 0) x = 0;  // zeros and shared values: exact coordinates
    return x;
  }
};

struct Tally {
  int tried = 0, on_stack = 0;
};

/// Random edges across random planes: where the stack integers give the doubles, they
/// are the truncated rationals; so are the crossing's own doubles and lazy rationals.
Tally check_edge_plane_crossings(int binades, int count, uint64_t seed) {
  Coordinates c{std::mt19937_64(seed), binades};
  Tally tally;
  while (tally.tried < count) {
    QPoint::Recipe r{QPoint::Recipe::kEdgePlane, 0, 0, {}};
    for (double& v : r.v) v = c();
    if (c.rng() % 8 == 0) r.v[3] = r.v[0] + std::ldexp(1.0, -40);  // nearly along the plane
    const double *a = r.v, *b = r.v + 3, *f0 = r.v + 6, *f1 = r.v + 9, *f2 = r.v + 12;
    const int sa = orient3d(f0, f1, f2, a), sb = orient3d(f0, f1, f2, b);
    if (sa == 0 || sb == 0 || sa == sb) continue;
    ++tally.tried;
    const mpq_class oa = orient3d_exact(f0, f1, f2, a), ob = orient3d_exact(f0, f1, f2, b);
    std::array<double, 3> d;
    if (truncated_crossing_on_stack(r, d)) {
      ++tally.on_stack;
      for (int k = 0; k < 3; ++k) EXPECT_EQ(d[size_t(k)], truncated(oa, ob, a, b, k)) << "seed " << seed << " k " << k;
    }
    const QPoint p = edge_plane_crossing(a, b, f0, f1, f2);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(p.d[size_t(k)], truncated(oa, ob, a, b, k));
      EXPECT_EQ(p.q(k), mpq_class(Q(a[k]) + oa / (oa - ob) * (Q(b[k]) - Q(a[k]))));
    }
  }
  return tally;
}

/// The same for segments against lines in the projection on axes (i, j).
Tally check_segment_line_crossings(int binades, int count, uint64_t seed) {
  Coordinates c{std::mt19937_64(seed), binades};
  Tally tally;
  while (tally.tried < count) {
    const int i = int(c.rng() % 3), j = (i + 1 + int(c.rng() % 2)) % 3;
    double a[3], b[3], c0[3], c1[3];
    for (int k = 0; k < 3; ++k) { a[k] = c(); b[k] = c(); c0[k] = c(); c1[k] = c(); }
    const int sa = orient2d(c0, c1, a, i, j), sb = orient2d(c0, c1, b, i, j);
    if (sa == 0 || sb == 0 || sa == sb) continue;
    ++tally.tried;
    auto side = [&](const double* x) -> mpq_class {
      return (Q(c1[i]) - Q(c0[i])) * (Q(x[j]) - Q(c0[j])) - (Q(c1[j]) - Q(c0[j])) * (Q(x[i]) - Q(c0[i]));
    };
    const mpq_class oa = side(a), ob = side(b);
    QPoint::Recipe r{QPoint::Recipe::kSegmentLine, static_cast<signed char>(i), static_cast<signed char>(j),
                     {a[0], a[1], a[2], b[0], b[1], b[2], c0[i], c0[j], c1[i], c1[j]}};
    std::array<double, 3> d;
    if (truncated_crossing_on_stack(r, d)) {
      ++tally.on_stack;
      for (int k = 0; k < 3; ++k) EXPECT_EQ(d[size_t(k)], truncated(oa, ob, a, b, k)) << "seed " << seed << " k " << k;
    }
    const QPoint p = segment_line_crossing(a, b, c0, c1, i, j);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(p.d[size_t(k)], truncated(oa, ob, a, b, k));
      EXPECT_EQ(p.q(k), mpq_class(Q(a[k]) + oa / (oa - ob) * (Q(b[k]) - Q(a[k]))));
    }
  }
  return tally;
}

}  // namespace

TEST(UnionCrossingDoubles, EdgePlaneCrossingsAreTheTruncatedRationals) {
  // Uniform coordinates take the 256-bit integers, exponents spread over 40 binades the
  // 512-bit ones, over 120 often neither (rationals then).
  const Tally uniform = check_edge_plane_crossings(0, 20000, 1);
  const Tally spread = check_edge_plane_crossings(40, 20000, 2);
  const Tally wide = check_edge_plane_crossings(120, 5000, 3);
  EXPECT_GT(uniform.on_stack, 0.9 * uniform.tried);
  EXPECT_GT(spread.on_stack, 0.9 * spread.tried);
  EXPECT_LT(wide.on_stack, 0.5 * wide.tried);
}

TEST(UnionCrossingDoubles, SegmentLineCrossingsAreTheTruncatedRationals) {
  const Tally uniform = check_segment_line_crossings(0, 20000, 4);
  const Tally spread = check_segment_line_crossings(40, 20000, 5);
  EXPECT_GT(uniform.on_stack, 0.9 * uniform.tried);
  EXPECT_GT(spread.on_stack, 0.9 * spread.tried);
}

TEST(UnionCrossingDoubles, CrossingsAtADoubleAreLeftToTheRationalsOrExact) {
  // Edge (0,0,0)-(1,1,1) crosses the plane x + y + z = 1.5 at (0.5, 0.5, 0.5), a double
  // none of the inputs holds: the leading bits cannot tell it from its neighbours.
  const double a[3] = {0, 0, 0}, b[3] = {1, 1, 1};
  const double f0[3] = {1.5, 0, 0}, f1[3] = {0, 1.5, 0}, f2[3] = {0, 0, 1.5};
  QPoint::Recipe r{QPoint::Recipe::kEdgePlane, 0, 0, {0, 0, 0, 1, 1, 1, 1.5, 0, 0, 0, 1.5, 0, 0, 0, 1.5}};
  std::array<double, 3> d{};
  if (truncated_crossing_on_stack(r, d)) {
    for (double x : d) EXPECT_EQ(x, 0.5);
  }
  const QPoint p = edge_plane_crossing(a, b, f0, f1, f2);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(p.d[size_t(k)], 0.5);
    EXPECT_EQ(p.q(k), mpq_class(1, 2));
  }
}

TEST(UnionCrossingDoubles, CopiesOfALazyCrossingBuildTheSameRationals) {
  const double a[3] = {0.1, 0.2, -0.3}, b[3] = {0.7, -0.4, 0.9};
  const double f0[3] = {-1, -1, 0.05}, f1[3] = {1, -1, 0.2}, f2[3] = {0, 1, 0.1};
  const QPoint p = edge_plane_crossing(a, b, f0, f1, f2);
  const QPoint copy(p);  // before p built its rationals
  QPoint moved = QPoint(p);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(copy.q(k), p.q(k));
    EXPECT_EQ(moved.q(k), p.q(k));
    EXPECT_EQ(copy.d[size_t(k)], p.d[size_t(k)]);
  }
  EXPECT_TRUE(same_point(copy, p));
}
