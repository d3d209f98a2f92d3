// Unit tests of the union's exact building blocks.
#include "union/candidate_pairs.h"
#include "union/exact.h"
#include "union/face_clearance.h"
#include "union/face_triangulation.h"
#include "union/link_triangulation.h"
#include "union/point_table.h"
#include "union/same_cover.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <random>
#include <thread>
#include <vector>

using namespace mr::surface_union;

TEST(UnionExact, Orient3dIsExactOnNearlyCoplanarPoints) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
  const double up[3] = {0.3, 0.3, 1e-300}, down[3] = {0.3, 0.3, -1e-300}, on[3] = {0.3, 0.3, 0};
  EXPECT_EQ(orient3d(a, b, c, up), 1);
  EXPECT_EQ(orient3d(a, b, c, down), -1);
  EXPECT_EQ(orient3d(a, b, c, on), 0);
  // A plane that is not axis-aligned: points on it computed in doubles are usually
  // off it by rounding, which the exact sign must see.
  const double p[3] = {0.1, 0.2, 0.3}, q[3] = {1.7, -0.4, 0.9}, r[3] = {0.5, 2.3, -1.1};
  const double mid[3] = {(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2};
  const int s = orient3d(p, q, r, mid);
  EXPECT_EQ(s, sgn(orient3d_exact(p, q, r, mid)));
  const double exact_mid[3] = {0.5, 0.5, 0.5}, e0[3] = {0, 0, 0}, e1[3] = {1, 1, 1}, e2[3] = {1, 0, 1};
  EXPECT_EQ(orient3d(e0, e1, e2, exact_mid), 0);
}

TEST(UnionExact, PointTableSharesEqualRationals) {
  PointTable t;
  const int a = t.insert(make_point(mpq_class(1, 3), mpq_class(0), mpq_class(2, 7)));
  const int b = t.insert(make_point(mpq_class(2, 6), mpq_class(0), mpq_class(4, 14)));
  const int c = t.insert(make_point(mpq_class(1, 3) + mpq_class(1, 1000000000) * mpq_class(1, 1000000000), mpq_class(0), mpq_class(2, 7)));
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  EXPECT_EQ(t.size(), 2);
}

TEST(UnionExact, Orient2dOnDoublesIsExactOnNearlyCollinearPoints) {
  // Three points on the line y = x / 3 as closely as doubles allow: the filter cannot
  // decide, the integer fallback must agree with rational arithmetic.
  const double a[3] = {0.1, 0.1 / 3, 0}, b[3] = {0.7, 0.7 / 3, 0}, c[3] = {1.3, 1.3 / 3, 0};
  const int s = orient2d(a, b, c, 0, 1);
  EXPECT_EQ(s, sgn(orient2d_exact(make_point({a[0], a[1], a[2]}), make_point({b[0], b[1], b[2]}),
                                  make_point({c[0], c[1], c[2]}), 0, 1)));
  const double p[3] = {0.25, 0.5, 0}, q[3] = {0.75, 1.5, 0}, r[3] = {1.0, 2.0, 0};  // exactly collinear
  EXPECT_EQ(orient2d(p, q, r, 0, 1), 0);
  const double up[3] = {1.0, std::nextafter(2.0, 3.0), 0};
  EXPECT_EQ(orient2d(p, q, up, 0, 1), 1);
}

namespace {

/// Crossings of a few segments with line (c0, c1) in the xy projection: points with
/// unreduced rational coordinates lying exactly on that line.
std::vector<QPoint> crossings_on_line(const double* c0, const double* c1) {
  std::vector<QPoint> out;
  for (int k = 0; k < 4; ++k) {
    const double s0[3] = {0.2 + 0.13 * k, -0.1, 0.3 * k}, s1[3] = {0.3 + 0.07 * k, 1.1, 1.0 / 3 - 0.1 * k};
    out.push_back(segment_line_crossing(s0, s1, c0, c1, 0, 1));
  }
  return out;
}

}  // namespace

TEST(UnionExact, Orient2dOnUnreducedRationalsAgreesWithRationalArithmetic) {
  // Points exactly on line L = (c0, c1), and on L' whose end is one ulp off c1: most
  // triples are exactly collinear or off by ~1e-17, where the filter cannot decide.
  const double c0[3] = {0.1, 0.3, 0}, c1[3] = {0.7, 0.5, 0}, c1_off[3] = {0.7, std::nextafter(0.5, 1.0), 0};
  std::vector<QPoint> pts = crossings_on_line(c0, c1);
  for (QPoint& p : crossings_on_line(c0, c1_off)) pts.push_back(std::move(p));
  pts.push_back(make_point({c0[0], c0[1], c0[2]}));
  pts.push_back(make_point({c1[0], c1[1], c1[2]}));
  const int n = int(pts.size());
  const int axes[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  // First on the unreduced forms (orient2d_exact below puts them in canonical form),
  // then again on the canonical forms (one denominator per coordinate).
  std::vector<int> signs;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> got;
    for (const auto& ax : axes)
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
          for (int c = 0; c < n; ++c)
            if (a != b && b != c && a != c) got.push_back(orient2d(pts[a], pts[b], pts[c], ax[0], ax[1]));
    if (pass == 0) {
      int undecided_zero = 0, undecided_nonzero = 0;
      size_t t = 0;
      for (const auto& ax : axes)
        for (int a = 0; a < n; ++a)
          for (int b = 0; b < n; ++b)
            for (int c = 0; c < n; ++c) {
              if (a == b || b == c || a == c) continue;
              const int expected = sgn(orient2d_exact(pts[a], pts[b], pts[c], ax[0], ax[1]));
              if (orient2d_filter(pts[a], pts[b], pts[c], ax[0], ax[1]) == 2)
                ++(expected == 0 ? undecided_zero : undecided_nonzero);
              signs.push_back(expected);
              EXPECT_EQ(got[t++], expected) << a << " " << b << " " << c << " on axes " << ax[0] << ax[1];
            }
      // Both kinds of exact decisions were made: collinear, and a sign the filter missed.
      EXPECT_GT(undecided_zero, 100);
      EXPECT_GT(undecided_nonzero, 100);
    } else {
      EXPECT_EQ(got, signs);
    }
  }
}

TEST(UnionExact, Orient3dOnUnreducedRationalsAgreesWithRationalArithmetic) {
  // Crossings of edges with plane F, and with F' whose corner is one ulp off: most
  // quadruples are exactly coplanar or off by ~1e-17, where the filter cannot decide.
  const double f0[3] = {0.1, 0.2, 0.3}, f1[3] = {0.9, 0.1, 0.4}, f2[3] = {0.2, 0.8, 0.6};
  const double f2_off[3] = {0.2, 0.8, std::nextafter(0.6, 1.0)};
  std::vector<QPoint> pts;
  for (const double* corner : {f2, f2_off})
    for (int k = 0; k < 6; ++k) {
      const double a[3] = {0.15 + 0.1 * k, 0.2 + 0.05 * k, -1}, b[3] = {0.3 + 0.07 * k, 0.25 - 0.03 * k, 2};
      pts.push_back(edge_plane_crossing(a, b, f0, f1, corner));
    }
  pts.push_back(make_point({f0[0], f0[1], f0[2]}));
  const int n = int(pts.size());
  auto exact_sign = [&](int a, int b, int c, int d) {
    mpq_class m[3][3];
    for (int k = 0; k < 3; ++k) {
      m[0][k] = pts[b].q(k) - pts[a].q(k);
      m[1][k] = pts[c].q(k) - pts[a].q(k);
      m[2][k] = pts[d].q(k) - pts[a].q(k);
    }
    return sgn(mpq_class(m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])));
  };
  // The predicate first (on the unreduced forms: the reference puts them in canonical form).
  std::vector<std::array<int, 5>> got;
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      for (int c = b + 1; c < n; ++c)
        for (int d = 0; d < n; ++d)
          if (d != a && d != b && d != c) got.push_back({a, b, c, d, orient3d(pts[a], pts[b], pts[c], pts[d])});
  int zero = 0, nonzero = 0;
  for (const auto& g : got) {
    const int expected = exact_sign(g[0], g[1], g[2], g[3]);
    ++(expected == 0 ? zero : nonzero);
    EXPECT_EQ(g[4], expected) << g[0] << " " << g[1] << " " << g[2] << " " << g[3];
  }
  EXPECT_GT(zero, 100);
  EXPECT_GT(nonzero, 100);
}

TEST(UnionExact, RationalCrossingEqualsTheInterpolatedPoint) {
  // Segment (a, b) between two unreduced points, crossing line (c, d) of unreduced
  // points: the integer construction gives the rational a + t (b - a), t = oa / (oa - ob).
  const double l0[3] = {0, 0, 0}, l1[3] = {1, 1, 0}, m0[3] = {0, 0.8, 0}, m1[3] = {1, 0.2, 0};
  std::vector<QPoint> on_l = crossings_on_line(l0, l1), on_m = crossings_on_line(m0, m1);
  const QPoint x = segment_line_crossing(on_l[0], on_l[3], on_m[1], on_m[2], 0, 1);
  const QPoint& a = on_l[0];
  const QPoint& b = on_l[3];
  const mpq_class oa = orient2d_exact(on_m[1], on_m[2], a, 0, 1), ob = orient2d_exact(on_m[1], on_m[2], b, 0, 1);
  ASSERT_LT(sgn(oa) * sgn(ob), 0);
  const QPoint y = lerp(a, b, oa / (oa - ob));
  EXPECT_EQ(x.d, y.d);
  EXPECT_TRUE(same_point(x, y));  // before x is put in canonical form
  for (int k = 0; k < 3; ++k) EXPECT_EQ(compare(x, y, k), 0);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(x.q(k), y.q(k));
  EXPECT_EQ(orient2d(on_m[1], on_m[2], x, 0, 1), 0);
  EXPECT_EQ(orient2d(a, b, x, 0, 1), 0);
}

TEST(UnionExact, UnreducedAndCanonicalFormsCompareAsEqual) {
  // (0,0)-(2,2) crosses x + y = 1 at (1/2, 1/2), built as 2/4; an ulp above 1/2 is
  // another point with the same truncated x only if the doubles say so: compare decides.
  const double s0[3] = {0, 0, 5}, s1[3] = {2, 2, 5}, l0[3] = {1, 0, 5}, l1[3] = {0, 1, 5};
  const QPoint c = segment_line_crossing(s0, s1, l0, l1, 0, 1);
  const QPoint half = make_point(mpq_class(1, 2), mpq_class(1, 2), mpq_class(5));
  const QPoint above = make_point(mpq_class(1, 2) + mpq_class(1, 1000000) * mpq_class(1, 1000000) * mpq_class(1, 1000000),
                                  mpq_class(1, 2), mpq_class(5));
  EXPECT_TRUE(same_point(c, half));
  EXPECT_TRUE(same_point(c, make_point({0.5, 0.5, 5})));
  EXPECT_EQ(compare(c, above, 0), -1);
  EXPECT_EQ(compare(above, c, 0), 1);
  EXPECT_FALSE(same_point(c, above));
}

TEST(UnionExact, ExactOrient2dReadsPointsWhileAnotherThreadCanonicalisesThem) {
  // Threads share unreduced points, as in the re-triangulation: one reads their stored
  // forms for the integer predicates while the other puts them in canonical form in
  // place (q()). ThreadSanitizer (scripts/test) checks the locks and atomics; it does
  // not see the reads and writes inside GMP, so the results are checked too: a form read
  // half reduced would make these collinear points look not collinear (a race would
  // show only by chance, the window is short).
  const double c0[3] = {0.1, 0.3, 0}, c1[3] = {0.7, 0.5, 0};
  constexpr int kRounds = 2000;
  std::vector<std::vector<QPoint>> sets;
  for (int r = 0; r < kRounds; ++r) sets.push_back(crossings_on_line(c0, c1));
  std::atomic<int> arrived{0}, wrong{0};
  auto wait_for_other = [&](int round) {  // both threads work on a round's points at once
    arrived.fetch_add(1);
    while (arrived.load() < 2 * (round + 1)) std::this_thread::yield();
  };
  std::thread reader([&] {
    for (int r = 0; r < kRounds; ++r) {
      wait_for_other(r);
      const auto& p = sets[r];
      for (int a = 0; a < 4; ++a) {
        if (orient2d(p[a], p[(a + 1) % 4], p[(a + 2) % 4], 0, 1) != 0) ++wrong;
        if (!same_point(p[a], p[a]) || compare(p[a], p[(a + 1) % 4], 0) == 0) ++wrong;
      }
    }
  });
  for (int r = 0; r < kRounds; ++r) {
    wait_for_other(r);
    for (const QPoint& p : sets[r]) (void)p.q(0);
  }
  reader.join();
  EXPECT_EQ(wrong.load(), 0);
}

TEST(UnionExact, CrossingsAreExactAndEqualToTheReducedRational) {
  // Edge (a, b) crosses plane z = 1/3 (through three points): the lazily reduced point
  // equals the point built from rationals, and a second construction finds it in the table.
  const double a[3] = {0.1, 0.2, 0}, b[3] = {0.9, 0.4, 1};
  const double f0[3] = {0, 0, 1.0 / 3}, f1[3] = {1, 0, 1.0 / 3}, f2[3] = {0, 1, 1.0 / 3};
  const QPoint x = edge_plane_crossing(a, b, f0, f1, f2);
  const mpq_class t = mpq_class(1.0 / 3);  // z of the plane; z(a) = 0, z(b) = 1
  const QPoint y = lerp(make_point({a[0], a[1], a[2]}), make_point({b[0], b[1], b[2]}), t);
  EXPECT_TRUE(same_point(x, y));
  for (int k = 0; k < 3; ++k) EXPECT_EQ(x.q(k), y.q(k));
  PointTable table;
  EXPECT_EQ(table.insert(QPoint(x)), table.insert(QPoint(y)));
  // Coplanar segment against a line: (0,0)-(2,2) crosses x + y = 1 at (1/2, 1/2).
  const double s0[3] = {0, 0, 5}, s1[3] = {2, 2, 5}, l0[3] = {1, 0, 5}, l1[3] = {0, 1, 5};
  const QPoint c = segment_line_crossing(s0, s1, l0, l1, 0, 1);
  EXPECT_EQ(c.q(0), mpq_class(1, 2));
  EXPECT_EQ(c.q(1), mpq_class(1, 2));
  EXPECT_EQ(c.q(2), mpq_class(5));
}

TEST(UnionExact, AxisParallelCrossingsAreDoublesEqualToTheRationals) {
  // An edge along y crosses the plane y = 1/3: the crossing is built from doubles, and
  // it is the rational point a + t (b - a).
  const double a[3] = {0.3, 0.1, 0.7}, b[3] = {0.3, 0.9, 0.7};
  const double c = 1.0 / 3;
  const double f0[3] = {0, c, 0}, f1[3] = {1, c, 0}, f2[3] = {0, c, 1};
  const QPoint x = edge_plane_crossing(a, b, f0, f1, f2);
  EXPECT_TRUE(x.exact_double);
  const mpq_class t = (mpq_class(c) - mpq_class(a[1])) / (mpq_class(b[1]) - mpq_class(a[1]));
  const QPoint y = lerp(make_point({a[0], a[1], a[2]}), make_point({b[0], b[1], b[2]}), t);
  EXPECT_TRUE(same_point(x, y));
  for (int k = 0; k < 3; ++k) EXPECT_EQ(x.q(k), y.q(k));
  // In the plane z = 5: a segment along y against a line along x.
  const double s0[3] = {0.25, 0, 5}, s1[3] = {0.25, 2, 5}, l0[3] = {0, 0.7, 5}, l1[3] = {1, 0.7, 5};
  const QPoint p = segment_line_crossing(s0, s1, l0, l1, 0, 1);
  EXPECT_TRUE(p.exact_double);
  EXPECT_EQ(p.q(0), mpq_class(0.25));
  EXPECT_EQ(p.q(1), mpq_class(0.7));
  EXPECT_EQ(p.q(2), mpq_class(5));
  // A diagonal line: the rational path, the same point as before the shortcut.
  const double d0[3] = {0, 0.5, 5}, d1[3] = {1, 0.9, 5};
  const QPoint q = segment_line_crossing(s0, s1, d0, d1, 0, 1);
  EXPECT_FALSE(q.exact_double);
  EXPECT_EQ(q.q(1), mpq_class(0.5) + mpq_class(0.25) * (mpq_class(0.9) - mpq_class(0.5)));
}

TEST(UnionExact, PointsBuiltOnALineAreKnownCollinear) {
  PointTable t;
  const int u = t.insert(make_point({0, 0, 0})), w = t.insert(make_point({3, 0, 0}));
  const int p = t.insert_on_line(make_point(mpq_class(1), mpq_class(0), mpq_class(0)), u, w);
  const int q = t.insert_on_line(make_point(mpq_class(2), mpq_class(0), mpq_class(0)), w, u);
  const int off = t.insert(make_point({1, 1, 0}));
  EXPECT_TRUE(t.known_collinear(u, p, w));
  EXPECT_TRUE(t.known_collinear(p, q, u));
  EXPECT_FALSE(t.known_collinear(u, p, off));
}

/// The triangles' area in the xy-plane, each checked to turn counter-clockwise there.
double counter_clockwise_area(const PointTable& t, const std::vector<std::array<int, 3>>& triangles) {
  double area = 0;
  for (const auto& f : triangles) {
    const auto &a = t[f[0]].d, &b = t[f[1]].d, &c = t[f[2]].d;
    const double twice = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    EXPECT_GT(twice, 0);
    area += twice / 2;
  }
  return area;
}

TEST(UnionTriangulation, CrossingSegmentsSplitAndTileTheFace) {
  PointTable t;
  const int c0 = t.insert(make_point({0, 0, 0})), c1 = t.insert(make_point({4, 0, 0})), c2 = t.insert(make_point({0, 4, 0}));
  const int p = t.insert(make_point({1, 0.5, 0})), q = t.insert(make_point({1, 2, 0}));
  const int r = t.insert(make_point({0.5, 1, 0})), s = t.insert(make_point({2, 1, 0}));
  FaceConstraints fc;
  fc.segments = {{p, q}, {r, s}};
  std::vector<std::array<int, 3>> out;
  triangulate_face(t, {c0, c1, c2}, fc, out);
  EXPECT_EQ(t.size(), 8);  // the crossing (1, 1) was added
  EXPECT_DOUBLE_EQ(counter_clockwise_area(t, out), 8.0);
  // 8 points, 3 on the hull: 2*8 - 3 - 2 = 11 triangles.
  EXPECT_EQ(out.size(), 11u);
}

TEST(UnionTriangulation, AGridOfSegmentsTilesTheFaceAndTheNextFaceIsUnaffected) {
  // Six horizontal and six vertical segments: 24 ends and 36 crossings, more points
  // than the triangulator scans for, so it looks them up in its map.
  PointTable t;
  const int c0 = t.insert(make_point({0, 0, 0})), c1 = t.insert(make_point({4, 0, 0})), c2 = t.insert(make_point({0, 4, 0}));
  FaceConstraints fc;
  for (int k = 0; k < 6; ++k) {
    const double y = 0.3 + 0.25 * k, x = 0.35 + 0.25 * k;
    fc.segments.push_back({t.insert(make_point({0.1, y, 0})), t.insert(make_point({2.0, y, 0}))});
    fc.segments.push_back({t.insert(make_point({x, 0.1, 0})), t.insert(make_point({x, 2.0, 0}))});
  }
  auto tile = [&](const std::array<int, 3>& corners, const FaceConstraints& c, double expected_area) {
    std::vector<std::array<int, 3>> out;
    triangulate_face(t, corners, c, out);
    EXPECT_NEAR(counter_clockwise_area(t, out), expected_area, 1e-12);
    return out;
  };
  const auto grid = tile({c0, c1, c2}, fc, 8.0);
  EXPECT_EQ(t.size(), 3 + 24 + 36);
  EXPECT_EQ(grid.size(), size_t(2 * 63 - 3 - 2));  // points 63, 3 on the hull
  // Every piece of every segment is an edge: each crossing has four neighbours on the grid.
  auto has_edge = [&](const std::vector<std::array<int, 3>>& tris, int a, int b) {
    for (const auto& f : tris)
      for (int z = 0; z < 3; ++z)
        if ((f[z] == a && f[(z + 1) % 3] == b) || (f[z] == b && f[(z + 1) % 3] == a)) return true;
    return false;
  };
  const int corner = t.insert(make_point({0.35, 0.3, 0})), right = t.insert(make_point({0.6, 0.3, 0}));
  const int up = t.insert(make_point({0.35, 0.55, 0}));
  EXPECT_EQ(t.size(), 63);  // all three are grid crossings already
  EXPECT_TRUE(has_edge(grid, corner, right));
  EXPECT_TRUE(has_edge(grid, corner, up));
  // The same face again gives the same triangles; then a small face, with the buffers
  // the large one left, is tiled on its own.
  EXPECT_EQ(tile({c0, c1, c2}, fc, 8.0), grid);
  const int d0 = t.insert(make_point({10, 0, 1})), d1 = t.insert(make_point({11, 0, 1}));
  const int d2 = t.insert(make_point({10, 1, 1}));
  EXPECT_EQ(tile({d0, d1, d2}, FaceConstraints{}, 0.5).size(), 1u);
}

TEST(UnionTriangulation, CrossingsWaitForTheCommitAndGetTheTablesIndex) {
  // Triangulating only reads the table (faces run in parallel); the crossing is a
  // placeholder until commit_face files it, under the index an equal point already has.
  PointTable t;
  const int c0 = t.insert(make_point({0, 0, 0})), c1 = t.insert(make_point({4, 0, 0})), c2 = t.insert(make_point({0, 4, 0}));
  const int p = t.insert(make_point({1, 0.5, 0})), q = t.insert(make_point({1, 2, 0}));
  const int r = t.insert(make_point({0.5, 1, 0})), s = t.insert(make_point({2, 1, 0}));
  const int elsewhere = t.insert(make_point({1, 1, 0}));  // the crossing, filed by another face
  FaceConstraints fc;
  fc.segments = {{p, q}, {r, s}};
  FaceTriangles face;
  triangulate_face(t, {c0, c1, c2}, fc, face);
  EXPECT_EQ(t.size(), 8);
  ASSERT_EQ(face.crossings.size(), 1u);
  int placeholders = 0;
  for (const auto& tri : face.triangles)
    for (int v : tri) placeholders += v == -1;
  EXPECT_EQ(placeholders, 4);  // the crossing is a corner of the four triangles around it
  std::vector<std::array<int, 3>> out;
  commit_face(t, face, out);
  EXPECT_EQ(t.size(), 8);
  EXPECT_EQ(out.size(), 11u);
  int at_crossing = 0;
  for (const auto& tri : out)
    for (int v : tri) {
      EXPECT_GE(v, 0);
      at_crossing += v == elsewhere;
    }
  EXPECT_EQ(at_crossing, 4);
  EXPECT_TRUE(t.known_collinear(p, elsewhere, q));
  EXPECT_TRUE(t.known_collinear(r, elsewhere, s));
}

TEST(UnionPairs, GridFindsOnlyOverlappingPairsOfDifferentBodies) {
  Soup s;
  s.body_count = 2;
  s.vertex = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {0.6, 0.4, 0}, {5, 5, 5}, {6, 5, 5}, {5, 6, 5}};
  s.face = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
  s.body = {0, 1, 1};
  const auto pairs = candidate_pairs(s);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], std::make_pair(0, 1));
}

TEST(UnionClearance, TrianglesMeetOnlyBeyondWhatTheyShare) {
  const std::array<int, 3> f{0, 1, 2};
  const V3 F[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  // Coplanar neighbours at one corner, with a side on the line of F's side (a straight
  // intersection line): they share only the corner.
  const V3 G[3] = {{0, 0, 0}, {-1, 0, 0}, {0, -1, 0}};
  EXPECT_FALSE(triangles_meet(f, F, {0, 3, 4}, G));
  // The same corner, but the second triangle folds over the first.
  const V3 H[3] = {{0, 0, 0}, {0.5, 0.1, 0}, {0.1, 0.5, 0}};
  EXPECT_TRUE(triangles_meet(f, F, {0, 5, 6}, H));
  // Across a 90-degree crease, touching F's plane with one side only along F's side.
  const V3 C[3] = {{0.2, 0, 0}, {0.8, 0, 0}, {0.5, 0, -1}};
  EXPECT_TRUE(triangles_meet(f, F, {7, 8, 9}, C));  // lies on F's side: they meet there
  const V3 D[3] = {{1.2, 0, 0}, {1.8, 0, 0}, {1.5, 0, -1}};
  EXPECT_FALSE(triangles_meet(f, F, {7, 8, 9}, D));  // on the line beyond F's corner
  // Across a crease with a shared corner: a side along F's side meets it, one leaving the
  // corner away from F does not.
  const V3 K[3] = {{0, 0, 0}, {0.5, 0, 0}, {0.2, 0, -1}};
  EXPECT_TRUE(triangles_meet(f, F, {0, 14, 15}, K));
  const V3 L[3] = {{0, 0, 0}, {-0.5, 0, 0}, {-0.2, 0, -1}};
  EXPECT_FALSE(triangles_meet(f, F, {0, 14, 15}, L));
  // A thin plate: a parallel triangle 1e-15 above does not meet, one through F does.
  const V3 up[3] = {{0, 0, 1e-15}, {1, 0, 1e-15}, {0, 1, 1e-15}};
  EXPECT_FALSE(triangles_meet(f, F, {10, 11, 12}, up));
  const V3 through[3] = {{0.2, 0.2, -1}, {0.2, 0.2, 1}, {0.3, 0.2, 1}};
  EXPECT_TRUE(triangles_meet(f, F, {10, 11, 12}, through));
  // Neighbours across an edge never meet elsewhere.
  const V3 N[3] = {{1, 0, 0}, {0, 0, 0}, {0.5, -1, 0.3}};
  EXPECT_FALSE(triangles_meet(f, F, {1, 0, 13}, N));
}

// Faces each strictly across the other's plane take a shortcut (two orientations along
// the planes' common line); it must agree with testing every side against the other
// face. On a small integer grid many sides pass exactly through a corner or a side.
TEST(UnionClearance, TrianglesAcrossEachOthersPlaneMeetAsTheirSidesTell) {
  auto side_meets = [](const V3& p, const V3& q, const V3 T[3]) {  // p, q strictly apart
    const int s0 = orient3d(p.data(), q.data(), T[0].data(), T[1].data());
    const int s1 = orient3d(p.data(), q.data(), T[1].data(), T[2].data());
    const int s2 = orient3d(p.data(), q.data(), T[2].data(), T[0].data());
    return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
  };
  auto crosses = [&](const V3 A[3], const V3 B[3]) {  // a side of A through B
    int s[3];
    for (int i = 0; i < 3; ++i) s[i] = orient3d(B[0].data(), B[1].data(), B[2].data(), A[i].data());
    for (int i = 0; i < 3; ++i)
      if (s[i] * s[(i + 1) % 3] < 0 && side_meets(A[i], A[(i + 1) % 3], B)) return true;
    return false;
  };
  std::mt19937 rng(7);
  int meet = 0, apart = 0;
  for (int round = 0; round < 40000; ++round) {
    const bool grid = round % 2 == 0;
    std::uniform_int_distribution<int> cell(0, 3);
    std::uniform_real_distribution<double> real(-1, 1);
    V3 F[3], G[3];
    for (V3* T : {F, G})
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) T[i][k] = grid ? double(cell(rng)) : real(rng);
    bool straddle = true;
    for (int side = 0; side < 2; ++side) {
      const V3* A = side == 0 ? F : G;
      const V3* B = side == 0 ? G : F;
      int pos = 0, neg = 0;
      for (int i = 0; i < 3; ++i) {
        const int o = orient3d(A[0].data(), A[1].data(), A[2].data(), B[i].data());
        pos += o > 0;
        neg += o < 0;
      }
      straddle = straddle && pos > 0 && neg > 0 && pos + neg == 3;
    }
    if (!straddle) continue;
    const bool expected = crosses(F, G) || crosses(G, F);
    ASSERT_EQ(triangles_meet({0, 1, 2}, F, {3, 4, 5}, G), expected) << "round " << round;
    ++(expected ? meet : apart);
  }
  EXPECT_GT(meet, 1000);
  EXPECT_GT(apart, 1000);
}

TEST(UnionClearance, FlatConvexQuadOnlyWhenExactlyFlatAndConvex) {
  // Faces (u, v, c) and (v, u, d) on the plane z = 0.5, the diagonals crossing inside.
  const V3 u{0, 0, 0.5}, v{1, 1, 0.5}, c{0, 1, 0.5}, d{1, 0, 0.5};
  EXPECT_TRUE(flat_convex_quad(u, v, c, d));
  // d pushed to the reflex side: the new diagonal would leave the quad.
  EXPECT_FALSE(flat_convex_quad(u, v, c, V3{0.4, 0.6, 0.5}));
  // d on the line of (u, c): not strictly convex.
  EXPECT_FALSE(flat_convex_quad(u, v, c, V3{0, -1, 0.5}));
  // d 1e-16 off the plane: the flip moves the surface (a little).
  EXPECT_FALSE(flat_convex_quad(u, v, c, V3{1, 0, 0.5 + 1e-16}));
  // Tilted but exactly flat (small integers): accepted.
  EXPECT_TRUE(flat_convex_quad(V3{0, 0, 0}, V3{1, 1, 2}, V3{0, 1, 1}, V3{1, 0, 1}));
}

TEST(UnionClearance, GridFindsFacesAtTheirNewPlace) {
  std::vector<V3> v{{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}, {5, 5, 5}, {5.1, 5, 5}, {5, 5.1, 5}, {-10, 0, 0}, {10, 0, 0}, {0, 10, 0}};
  std::vector<std::array<int, 3>> f{{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};  // small, small far away, large
  FaceGrid grid(v, f);
  std::vector<int> near;
  grid.near({0.05, 0.01, -0.1}, {0.06, 0.02, 0.1}, near);
  std::sort(near.begin(), near.end());
  EXPECT_EQ(near, (std::vector<int>{0, 2}));
  for (int k = 3; k < 6; ++k) v[k][2] -= 5;  // the far face moves next to the others
  grid.add(1);
  grid.near({5.05, 5.01, -0.1}, {5.06, 5.02, 0.1}, near);  // also inside the large face's box
  std::sort(near.begin(), near.end());
  EXPECT_EQ(near, (std::vector<int>{1, 2}));
  grid.remove(1);
  grid.near({5.05, 5.01, -0.1}, {5.06, 5.02, 0.1}, near);
  EXPECT_EQ(near, (std::vector<int>{2}));
}

namespace {

std::vector<V3> regular_polygon(int k) {
  std::vector<V3> ring;
  for (int i = 0; i < k; ++i) ring.push_back({std::cos(2 * M_PI * i / k), std::sin(2 * M_PI * i / k), 0.0});
  return ring;
}

}  // namespace

TEST(UnionLinkTriangulation, BestTriangulationOfAHexagonAndItsConstraints) {
  const std::vector<V3> hex = regular_polygon(6);
  const V3 up{0, 0, 1};
  std::vector<std::array<int, 3>> tris;
  double angle = 0;
  ASSERT_TRUE(best_polygon_triangulation(hex, up, [](int, int) { return true; }, {-1, -1}, tris, angle));
  EXPECT_EQ(tris.size(), 4u);
  EXPECT_NEAR(angle * 180 / M_PI, 30.0, 1e-9);  // every triangulation of it has a 30 deg corner
  // Seen from below the polygon turns the other way: no triangle qualifies.
  EXPECT_FALSE(best_polygon_triangulation(hex, {0, 0, -1}, [](int, int) { return true; }, {-1, -1}, tris, angle));
  // Diagonal (0, 3) forced: both halves are fans of two triangles on it.
  ASSERT_TRUE(best_polygon_triangulation(hex, up, [](int, int) { return true; }, {3, 0}, tris, angle));
  int on_forced = 0;
  for (const auto& t : tris) {
    const bool has0 = t[0] == 0 || t[1] == 0 || t[2] == 0, has3 = t[0] == 3 || t[1] == 3 || t[2] == 3;
    on_forced += has0 && has3;
  }
  EXPECT_EQ(on_forced, 2);
  // With no diagonal at vertex 0 allowed, the triangulation cannot contain one.
  ASSERT_TRUE(best_polygon_triangulation(hex, up, [](int i, int) { return i != 0; }, {-1, -1}, tris, angle));
  for (const auto& t : tris) {
    if (t[0] != 0 && t[1] != 0 && t[2] != 0) continue;
    EXPECT_TRUE((t[0] == 1 || t[1] == 1 || t[2] == 1) && (t[0] == 5 || t[1] == 5 || t[2] == 5));
  }
  // No diagonal at all: impossible for more than three corners.
  EXPECT_FALSE(best_polygon_triangulation(hex, up, [](int, int) { return false; }, {-1, -1}, tris, angle));
}

TEST(UnionLinkTriangulation, BoundPrunesWithoutChangingTheBest) {
  // An irregular 9-gon: the bound below the optimum gives the same triangles and angle as
  // no bound; at or above the optimum there is no triangulation to give.
  std::vector<V3> ring;
  for (int i = 0; i < 9; ++i) {
    const double r = 1 + 0.3 * std::sin(2.7 * i), t = 2 * M_PI * i / 9 + 0.1 * std::cos(1.3 * i);
    ring.push_back({r * std::cos(t), r * std::sin(t), 0.05 * std::sin(5.0 * i)});
  }
  const V3 up{0, 0, 1};
  auto allowed = [](int i, int j) { return (i + j) % 4 != 1; };
  std::vector<std::array<int, 3>> free_tris, bound_tris;
  double free_angle = 0, bound_angle = 0;
  ASSERT_TRUE(best_polygon_triangulation(ring, up, allowed, {-1, -1}, free_tris, free_angle));
  ASSERT_TRUE(best_polygon_triangulation(ring, up, allowed, {-1, -1}, bound_tris, bound_angle, 0.9 * free_angle));
  EXPECT_EQ(bound_tris, free_tris);
  EXPECT_EQ(bound_angle, free_angle);
  EXPECT_FALSE(best_polygon_triangulation(ring, up, allowed, {-1, -1}, bound_tris, bound_angle, free_angle));
  EXPECT_FALSE(best_polygon_triangulation(ring, up, allowed, {-1, -1}, bound_tris, bound_angle, 1.0));
}

TEST(UnionLinkTriangulation, ReflexCornerIsNeverCut) {
  // An arrow: corner 2 is reflex, so diagonal (1, 3) would leave the polygon; the only
  // triangulations use diagonals from the reflex corner, and all triangles turn one way.
  const std::vector<V3> arrow{{0, 0, 0}, {2, -1, 0}, {1, 0, 0}, {2, 1, 0}};
  std::vector<std::array<int, 3>> tris;
  double angle = 0;
  ASSERT_TRUE(best_polygon_triangulation(arrow, {0, 0, 1}, [](int, int) { return true; }, {-1, -1}, tris, angle));
  ASSERT_EQ(tris.size(), 2u);
  for (const auto& t : tris) {
    const V3 &a = arrow[t[0]], &b = arrow[t[1]], &c = arrow[t[2]];
    EXPECT_GT((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]), 0);
  }
}

namespace {

// A star at vertex 0 on the crease between the planes z = 0 (y >= 0) and y = 0
// (z >= 0): line neighbours 1 and 2 on the x axis, 3 and 4 in z = 0, 5 and 6 in y = 0.
std::vector<V3> crease_points() {
  return {{0, 0, 0}, {-2, 0, 0}, {2, 0, 0}, {-1, 2, 0}, {1, 2, 0}, {1, 0, 2}, {-1, 0, 2}};
}

std::vector<PlacedFace> placed(const std::vector<std::array<int, 3>>& faces, const std::vector<V3>& at) {
  std::vector<PlacedFace> out;
  for (const auto& t : faces) out.push_back({t, {at[t[0]], at[t[1]], at[t[2]]}});
  return out;
}

const std::vector<std::array<int, 3>> kCreaseStar = {{0, 2, 4}, {0, 4, 3}, {0, 3, 1}, {0, 1, 6}, {0, 6, 5}, {0, 5, 2}};

}  // namespace

TEST(UnionSameCover, FlatStarFilledAgainCoversTheSame) {
  // A hexagon around vertex 0 in the tilted plane x + y + z = 1 (not across an axis),
  // its centre collapsed onto ring vertex 1.
  std::vector<V3> at = {{0, 0, 1}};
  const double ring[6][2] = {{2, 0}, {1, 2}, {-1, 2}, {-2, 0}, {-1, -2}, {1, -2}};
  for (const auto& r : ring) at.push_back({r[0], r[1], 1 - r[0] - r[1]});
  std::vector<std::array<int, 3>> fan, refilled;
  for (int i = 1; i <= 6; ++i) fan.push_back({0, i, i % 6 + 1});
  for (int i = 2; i <= 5; ++i) refilled.push_back({1, i, i + 1});
  EXPECT_TRUE(same_cover(placed(fan, at), placed(refilled, at)));
  // One new face turned over: not the same.
  refilled[1] = {1, 4, 3};
  EXPECT_FALSE(same_cover(placed(fan, at), placed(refilled, at)));
  // A face left out: a hole.
  refilled = {{1, 2, 3}, {1, 3, 4}, {1, 4, 5}};
  EXPECT_FALSE(same_cover(placed(fan, at), placed(refilled, at)));
}

TEST(UnionSameCover, VertexSlidAlongAStraightCreaseCoversTheSame) {
  const std::vector<V3> at = crease_points();
  const auto before = placed(kCreaseStar, at);
  auto moved = [&](const V3& p) {
    std::vector<V3> q = at;
    q[0] = p;
    return placed(kCreaseStar, q);
  };
  EXPECT_TRUE(same_cover(before, moved({0.5, 0, 0})));
  EXPECT_TRUE(same_cover(before, moved({-1.75, 0, 0})));
  EXPECT_FALSE(same_cover(before, moved({2.5, 0, 0})));     // past neighbour 2: faces turn over
  EXPECT_FALSE(same_cover(before, moved({0.5, 0, 1e-9})));  // off the plane z = 0
  EXPECT_FALSE(same_cover(before, moved({0.5, 1e-9, 0})));  // off the plane y = 0
}

TEST(UnionSameCover, CreaseVertexCollapsedOrRemovedAlongItsLineCoversTheSame) {
  const std::vector<V3> at = crease_points();
  const auto before = placed(kCreaseStar, at);
  // 0 onto its line neighbour 2: faces (0, 2, 4) and (0, 5, 2) go.
  EXPECT_TRUE(same_cover(before, placed({{2, 4, 3}, {2, 3, 1}, {2, 1, 6}, {2, 6, 5}}, at)));
  // 0 onto 4, off the crease: the faces in y = 0 fold into z = 0's side.
  EXPECT_FALSE(same_cover(before, placed({{4, 3, 1}, {4, 1, 6}, {4, 6, 5}, {4, 5, 2}}, at)));
  // 0 removed, its link filled with the line joined straight from 1 to 2.
  EXPECT_TRUE(same_cover(before, placed({{1, 2, 4}, {1, 4, 3}, {1, 6, 5}, {1, 5, 2}}, at)));
  // An open fan in z = 0 (vertex 0 on the border of what is shown) filled by one face:
  // the same only when 0 lies on the straight side from 3 to 1.
  for (double y0 : {0.0, 0.5}) {
    const std::vector<V3> fan_at = {{0, y0, 0}, {-2, 0, 0}, {0, 2, 0}, {2, 0, 0}};
    EXPECT_EQ(same_cover(placed({{0, 1, 2}, {0, 2, 3}}, fan_at), placed({{1, 2, 3}}, fan_at)), y0 == 0);
  }
}
