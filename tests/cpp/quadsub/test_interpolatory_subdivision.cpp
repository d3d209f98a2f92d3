#include "common/errors.h"
#include "quadsub/interpolatory_subdivision.h"
#include "quad_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

using namespace mr;
using namespace mr::quadsub;

namespace {
using test::grid;
using test::kPi;
using test::polygons;

// n sectors of k x k quads glued around one centre vertex of valence n, vertices jittered.
QuadMesh star(int n, int k, unsigned seed) {
  QuadMesh m = test::sector_fan(n, k);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  for (auto& p : m.points) p += Point3(jitter(rng), jitter(rng), 0.3 * std::sin(p[0]) * std::cos(p[1]) + jitter(rng));
  return m;
}

double bicubic(double x, double y) { return 0.3 * x * x * x - x * x * y + 0.7 * y * y * y + 0.2 * x * y * y * y + x - y; }
}  // namespace

TEST(QuadSub, DiagonalCorrectionMakesFacePointsAgreeAtValences3To6) {
  for (int n : {3, 5, 6}) {
    QuadMesh m = star(n, 4, 11 + n);
    std::vector<std::pair<Point3, Point3>> dirs;
    subdivide_step(m, {}, Params{}, nullptr, &dirs);
    int checked = 0;
    for (size_t q = 0; q < m.quads.size(); ++q) {
      if (m.quads[q][0] != 0) continue;  // faces at the extraordinary centre (vertex 0)
      EXPECT_LT((dirs[q].first - dirs[q].second).Norm(), 1e-12) << "valence " << n;
      ++checked;
    }
    EXPECT_EQ(checked, n);
  }
}

TEST(QuadSub, DerivedDiagonalWeightHoldsForOtherTensions) {
  // With w = 0.5 the weight -w/(8+w) (not the w = 1 value -1/9) makes both directions agree.
  QuadMesh m = star(5, 4, 3);
  Params p;
  p.w = 0.5;
  std::vector<std::pair<Point3, Point3>> dirs;
  subdivide_step(m, {}, p, nullptr, &dirs);
  for (size_t q = 0; q < m.quads.size(); ++q) {
    if (m.quads[q][0] == 0) { EXPECT_LT((dirs[q].first - dirs[q].second).Norm(), 1e-12); }
  }
  EXPECT_DOUBLE_EQ(diagonal_correction_weight(0.5), -0.5 / 8.5);
  EXPECT_DOUBLE_EQ(diagonal_correction_weight(1.0), -1.0 / 9.0);
}

TEST(QuadSub, OldVerticesNeverMoveBitForBit) {
  QuadMesh m = star(5, 3, 5);
  Params p;
  p.iterations = 2;
  Result r = subdivide(m.points, polygons(m), {}, p);
  for (size_t i = 0; i < m.points.size(); ++i) {
    EXPECT_EQ(r.mesh.points[i][0], m.points[i][0]);
    EXPECT_EQ(r.mesh.points[i][1], m.points[i][1]);
    EXPECT_EQ(r.mesh.points[i][2], m.points[i][2]);
  }
  EXPECT_EQ(r.mesh.quads.size(), m.quads.size() * 16);
  EXPECT_EQ(r.extraordinary_vertices, 1);
}

TEST(QuadSub, ReproducesBicubicsOnRegularGridsWithW1) {
  const int n = 10;
  QuadMesh m = grid(n, bicubic);
  Result r = subdivide(m.points, polygons(m), {}, Params{});
  // Refined vertices whose stencils stay inside the grid (two cells from the border).
  int checked = 0;
  for (const auto& p : r.mesh.points) {
    if (p[0] < 2.0 / n - 1e-9 || p[0] > 1 - 2.0 / n + 1e-9 || p[1] < 2.0 / n - 1e-9 || p[1] > 1 - 2.0 / n + 1e-9)
      continue;
    EXPECT_NEAR(p[2], bicubic(p[0], p[1]), 1e-12);
    ++checked;
  }
  EXPECT_EQ(checked, 13 * 13);  // x, y in {0.2, 0.25, ..., 0.8}
}

TEST(QuadSub, TensionZeroGivesMidpoints) {
  QuadMesh m = grid(4, [](double x, double y) { return std::sin(3 * x) * y; });
  Params p;
  p.w = 0;
  EdgeList none;
  QuadMesh out = subdivide_step(m, none, p, nullptr);
  // the new vertex between corners 0 and 1 of the first quad is their midpoint
  const auto& q = out.quads[0];
  Point3 mid = (m.points[m.quads[0][0]] + m.points[m.quads[0][1]]) * 0.5;
  EXPECT_LT((out.points[q[1]] - mid).Norm(), 1e-15);
}

TEST(QuadSub, PatchesSharingABoundaryPolygonStayJoined) {
  // Two grids side by side share the polygon x = 1; each is subdivided on its own.
  auto f = [](double x, double y) { return std::sin(2 * x) + y * y * y; };
  QuadMesh left = grid(5, f, 0.0), right = grid(5, f, 1.0);
  Params p;
  p.iterations = 2;
  Result rl = subdivide(left.points, polygons(left), {}, p);
  Result rr = subdivide(right.points, polygons(right), {}, p);
  std::vector<Point3> on_left, on_right;
  for (const auto& q : rl.mesh.points) if (q[0] == 1.0) on_left.push_back(q);
  for (const auto& q : rr.mesh.points) if (q[0] == 1.0) on_right.push_back(q);
  auto by_y = [](const Point3& a, const Point3& b) { return a[1] < b[1]; };
  std::sort(on_left.begin(), on_left.end(), by_y);
  std::sort(on_right.begin(), on_right.end(), by_y);
  ASSERT_EQ(on_left.size(), 21u);  // 5 * 4 + 1 vertices along the shared side
  ASSERT_EQ(on_left.size(), on_right.size());
  for (size_t i = 0; i < on_left.size(); ++i) {
    EXPECT_EQ(on_left[i][1], on_right[i][1]);
    EXPECT_EQ(on_left[i][2], on_right[i][2]);
  }
}

TEST(QuadSub, CreaseStaysSharpAndInterpolated) {
  // A grid folded by 90 degrees along x = 0.5: planes z = 0 and x = 0.5.
  const int n = 6;
  QuadMesh m = grid(n, [](double, double) { return 0.0; });
  for (auto& p : m.points)
    if (p[0] > 0.5) { p[2] = p[0] - 0.5; p[0] = 0.5; }
  EdgeList crease;
  for (int j = 0; j < n; ++j) crease.push_back({j * (n + 1) + n / 2, (j + 1) * (n + 1) + n / 2});
  auto off_planes = [](const QuadMesh& out) {
    int off = 0;
    for (const auto& p : out.points) {
      off += std::fabs(p[2]) > 1e-12 && std::fabs(p[0] - 0.5) > 1e-12;
    }
    return off;
  };
  Params p;
  p.iterations = 2;
  Result sharp = subdivide(m.points, polygons(m), crease, p);
  EXPECT_EQ(off_planes(sharp.mesh), 0);
  EXPECT_EQ(sharp.creases.size(), crease.size() * 4);
  Result smooth = subdivide(m.points, polygons(m), {}, p);
  EXPECT_GT(off_planes(smooth.mesh), 0);  // without the crease the fold is rounded
  Params by_angle = p;
  by_angle.crease_angle_deg = 45;
  Result detected = subdivide(m.points, polygons(m), {}, by_angle);
  EXPECT_EQ(off_planes(detected.mesh), 0);
}

TEST(QuadSub, ClosedCubeStaysClosedAndNonQuadsAreSplit) {
  std::vector<Point3> pts = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  std::vector<std::vector<int>> faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  Params p;
  p.iterations = 2;
  Result r = subdivide(pts, faces, {}, p);
  EXPECT_EQ(r.extraordinary_vertices, 8);
  std::map<std::pair<int, int>, int> uses;
  for (const auto& q : r.mesh.quads)
    for (int s = 0; s < 4; ++s) ++uses[std::minmax(q[s], q[(s + 1) % 4])];
  for (const auto& [e, c] : uses) EXPECT_EQ(c, 2);
  EXPECT_EQ(int(r.mesh.points.size()) - int(uses.size()) + int(r.mesh.quads.size()), 2);  // Euler
  // a triangle and a pentagon become 3 and 5 quads
  QuadMesh q = quads_from_polygons({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}, {1, 2, 0}},
                                   {{0, 1, 2}, {1, 3, 4, 5, 2}});
  EXPECT_EQ(q.quads.size(), 8u);
}

TEST(QuadSub, BadInputIsRejected) {
  QuadMesh m = grid(2, [](double, double) { return 0.0; });
  Params p;
  p.w = 1.3;
  EXPECT_THROW(subdivide(m.points, polygons(m), {}, p), InvalidInput);
  p.w = -0.1;
  EXPECT_THROW(subdivide(m.points, polygons(m), {}, p), InvalidInput);
  p = {};
  p.iterations = 0;
  EXPECT_THROW(subdivide(m.points, polygons(m), {}, p), InvalidInput);
  EXPECT_THROW(subdivide(m.points, {}, {}, Params{}), InvalidInput);
  auto bad = m.points;
  bad[0][0] = std::nan("");
  EXPECT_THROW(subdivide(bad, polygons(m), {}, Params{}), InvalidInput);
  // three quads on one edge
  std::vector<Point3> pts = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, -1, 0}, {0, -1, 0}, {1, 0, 1}, {0, 0, 1}};
  EXPECT_THROW(subdivide(pts, {{0, 1, 2, 3}, {1, 0, 5, 4}, {0, 1, 6, 7}}, {}, Params{}), TopologyError);
}

namespace {
// A cone z = 1 - |(x, y)| over a fan of n sectors of k x k quads around its tip (vertex 0):
// the lattice lines from the tip along sector borders are the cone's straight generators.
QuadMesh cone(int n, int k) {
  QuadMesh m = test::sector_fan(n, k);
  for (auto& p : m.points) p[2] = 1 - std::hypot(p[0], p[1]);
  return m;
}

// Mean angle (degrees) between the z axis and the normals of the quads touching vertex v.
double tilt_around(const QuadMesh& m, int v) {
  double sum = 0;
  int count = 0;
  for (const auto& q : m.quads) {
    if (std::find(q.begin(), q.end(), v) == q.end()) continue;
    Point3 nrm = (m.points[q[2]] - m.points[q[0]]) ^ (m.points[q[3]] - m.points[q[1]]);
    sum += std::acos(std::fabs(nrm[2]) / nrm.Norm()) * 180 / kPi;
    ++count;
  }
  return sum / count;
}
}  // namespace

TEST(QuadSub, CuspKeepsTheTipOfAConePointed) {
  for (int n : {4, 5}) {
    QuadMesh m = cone(n, 3);
    ASSERT_EQ(m.points[0], Point3(0, 0, 1));
    Params with_cusp;
    with_cusp.cusp_vertices = {0};
    // one step: edge points on the generators through the tip lie on them (linear precision)
    QuadMesh one = subdivide_step(m, {}, with_cusp, nullptr);
    QuadMesh smooth_one = subdivide_step(m, {}, Params{}, nullptr);
    int generators = 0;
    for (size_t q = 0; q < m.quads.size(); ++q) {
      if (m.quads[q][0] != 0) continue;  // quads at the tip start there
      const Point3 mid = (m.points[0] + m.points[m.quads[q][1]]) * 0.5;
      EXPECT_LT((one.points[one.quads[4 * q][1]] - mid).Norm(), 1e-14);
      EXPECT_GT(smooth_one.points[smooth_one.quads[4 * q][1]][2] - mid[2], 1e-3);  // rounded without
      ++generators;
    }
    EXPECT_EQ(generators, n);
    // three steps: the faces at the tip stay tilted like the cone (45 deg), not flattened
    with_cusp.iterations = 3;
    Params smooth;
    smooth.iterations = 3;
    Result pointed = subdivide(m.points, polygons(m), {}, with_cusp);
    Result rounded = subdivide(m.points, polygons(m), {}, smooth);
    EXPECT_EQ(pointed.cusps, 1);
    EXPECT_NEAR(tilt_around(pointed.mesh, 0), 45.0, 2.0) << "valence " << n;  // measured 45.6, 44.8
    EXPECT_LT(tilt_around(rounded.mesh, 0), 30.0) << "valence " << n;  // measured 23.5, 20.3
    EXPECT_EQ(pointed.mesh.points[0], m.points[0]);
  }
  Params bad;
  bad.cusp_vertices = {1000};
  QuadMesh m = cone(4, 2);
  EXPECT_THROW(subdivide(m.points, polygons(m), {}, bad), InvalidInput);
}

TEST(QuadSub, MixedPolygonMeshesAreSplitWithoutHangingMidpoints) {
  // a closed pentagonal prism: 2 pentagons, 5 side quads
  std::vector<Point3> pts;
  for (int z = 0; z < 2; ++z)
    for (int k = 0; k < 5; ++k) pts.push_back(Point3(std::cos(2 * kPi * k / 5), std::sin(2 * kPi * k / 5), z));
  std::vector<std::vector<int>> faces = {{4, 3, 2, 1, 0}, {5, 6, 7, 8, 9}};
  for (int k = 0; k < 5; ++k) faces.push_back({k, (k + 1) % 5, 5 + (k + 1) % 5, 5 + k});
  std::vector<int> polygon_of_quad;
  QuadMesh q = quads_from_polygons(pts, faces, &polygon_of_quad);
  // each pentagon -> 5 quads; each side quad lies on a strip from pentagon to pentagon -> 2 quads
  EXPECT_EQ(q.quads.size(), 20u);
  EXPECT_EQ(std::count(polygon_of_quad.begin(), polygon_of_quad.end(), 2), 2);
  auto closed = [](const QuadMesh& m) {
    std::map<std::pair<int, int>, int> directed;
    for (const auto& f : m.quads)
      for (int s = 0; s < 4; ++s) ++directed[{f[s], f[(s + 1) % 4]}];
    for (const auto& [e, c] : directed)
      if (c != 1 || !directed.count({e.second, e.first})) return false;
    return true;
  };
  EXPECT_TRUE(closed(q));
  Result r = subdivide(pts, faces, {}, Params{});
  EXPECT_TRUE(closed(r.mesh));
  EXPECT_EQ(r.mesh.quads.size(), 80u);
  // a pure quad mesh comes back unchanged
  QuadMesh g = grid(3, [](double, double) { return 0.0; });
  QuadMesh same = quads_from_polygons(g.points, polygons(g));
  EXPECT_EQ(same.quads, g.quads);
  EXPECT_EQ(same.points.size(), g.points.size());
}
