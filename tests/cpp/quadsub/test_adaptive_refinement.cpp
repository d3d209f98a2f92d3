#include "common/errors.h"
#include "quadsub/adaptive_refinement.h"
#include "quad_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>

using namespace mr;
using namespace mr::quadsub;

namespace {

using Polygons = std::vector<std::vector<int>>;

using test::grid;

double flat(double, double) { return 0.0; }

// A closed net with eight valence-3 vertices: the unit cube, twice refined uniformly (96 quads).
QuadMesh rounded_cube(int levels = 2) {
  std::vector<Point3> pts = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  Polygons faces = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  Params p;
  p.iterations = levels;
  return subdivide(pts, faces, {}, p).mesh;
}

using test::polygons;

Point3 centroid(const QuadMesh& m, int q) {
  Point3 c(0, 0, 0);
  for (int v : m.quads[q]) c += m.points[v];
  return c * 0.25;
}

template <class Pred>
std::vector<char> select(const QuadMesh& m, Pred pred) {
  std::vector<char> s(m.quads.size(), 0);
  for (int q = 0; q < int(m.quads.size()); ++q) s[q] = pred(centroid(m, q)) ? 1 : 0;
  return s;
}

// Faces of the result (quads then triangles) with their levels.
struct Faces {
  std::vector<std::vector<int>> corners;
  std::vector<int> level;
};

Faces faces_of(const AdaptiveResult& r) {
  Faces f;
  for (size_t q = 0; q < r.mesh.quads.size(); ++q) {
    f.corners.push_back({r.mesh.quads[q].begin(), r.mesh.quads[q].end()});
    f.level.push_back(r.quad_level[q]);
  }
  for (size_t t = 0; t < r.triangles.size(); ++t) {
    f.corners.push_back({r.triangles[t].begin(), r.triangles[t].end()});
    f.level.push_back(r.triangle_level[t]);
  }
  return f;
}

// Directed edge -> face. Conforming and closed: every directed edge once, its reverse once.
std::map<std::pair<int, int>, int> directed_edges(const Faces& f) {
  std::map<std::pair<int, int>, int> e;
  for (int i = 0; i < int(f.corners.size()); ++i) {
    const auto& c = f.corners[i];
    for (size_t k = 0; k < c.size(); ++k) {
      bool fresh = e.emplace(std::make_pair(c[k], c[(k + 1) % c.size()]), i).second;
      EXPECT_TRUE(fresh) << "directed edge used twice (non-manifold or flipped face)";
    }
  }
  return e;
}

int max_level_jump(const Faces& f) {
  int jump = 0;
  const auto edges = directed_edges(f);
  for (const auto& [e, face] : edges) {
    auto twin = edges.find({e.second, e.first});
    if (twin != edges.end()) jump = std::max(jump, std::abs(f.level[face] - f.level[twin->second]));
  }
  return jump;
}

bool has_quad(const AdaptiveResult& r, const std::array<int, 4>& q) {
  for (const auto& o : r.mesh.quads)
    for (int k = 0; k < 4; ++k)
      if (o[k] == q[0] && o[(k + 1) % 4] == q[1] && o[(k + 2) % 4] == q[2] && o[(k + 3) % 4] == q[3]) return true;
  return false;
}

AdaptiveResult refine_selected(const QuadMesh& m, const std::vector<char>& sel, int iterations) {
  Params p;
  p.iterations = iterations;
  return subdivide_adaptive(m.points, polygons(m), {}, sel, p, AdaptiveParams{});
}

}  // namespace

TEST(QuadSubAdaptive, AllFacesIsTheUniformScheme) {
  QuadMesh m = rounded_cube();
  Params p;
  p.iterations = 2;
  AdaptiveParams all;
  all.refine = RefineFaces::All;
  AdaptiveResult a = subdivide_adaptive(m.points, polygons(m), {}, {}, p, all);
  Result u = subdivide(m.points, polygons(m), {}, p);
  ASSERT_EQ(a.mesh.points.size(), u.mesh.points.size());
  for (size_t i = 0; i < u.mesh.points.size(); ++i) EXPECT_EQ(a.mesh.points[i], u.mesh.points[i]);
  EXPECT_EQ(a.mesh.quads.size(), u.mesh.quads.size());
  EXPECT_TRUE(a.triangles.empty());
  EXPECT_EQ(a.transition_faces, 0);
  EXPECT_EQ(a.levels, 2);
  EXPECT_EQ(a.refined_per_level, (std::vector<int>{96, 384}));
}

TEST(QuadSubAdaptive, OneSelectedQuadGetsOneHangingPointTemplatesAround) {
  QuadMesh m = grid(6, flat);
  std::vector<char> sel(m.quads.size(), 0);
  sel[2 * 6 + 2] = 1;  // an inner quad
  AdaptiveResult r = refine_selected(m, sel, 1);
  // 4 children; each of the 4 edge neighbours becomes 2 quads + 1 triangle; 31 quads unchanged
  EXPECT_EQ(r.mesh.quads.size(), 4u + 4 * 2 + 31);
  EXPECT_EQ(r.triangles.size(), 4u);
  EXPECT_EQ(r.transition_faces, 12);
  EXPECT_EQ(r.refined_per_level, std::vector<int>{1});
  EXPECT_EQ(r.balance_refinements, 0);
  EXPECT_EQ(max_level_jump(faces_of(r)), 1);
  // flat input: every new point is in the plane, on the segment or quad it refines
  for (const auto& p : r.mesh.points) EXPECT_EQ(p[2], 0.0);
}

TEST(QuadSubAdaptive, TwoAdjacentAndTwoOppositeHangingSidesAreAllQuads) {
  QuadMesh m = grid(6, flat);
  // an L of three quads around quad (3,3): it gets two adjacent hanging sides
  std::vector<char> sel(m.quads.size(), 0);
  sel[2 * 6 + 3] = sel[2 * 6 + 2] = sel[3 * 6 + 2] = 1;
  AdaptiveResult l = refine_selected(m, sel, 1);
  Faces fl = faces_of(l);
  int quads_at_3_3 = 0;
  const Point3 lo(3.0 / 6, 3.0 / 6, -1), hi(4.0 / 6, 4.0 / 6, 1);
  for (size_t i = 0; i < fl.corners.size(); ++i) {
    Point3 c(0, 0, 0);
    for (int v : fl.corners[i]) c += l.mesh.points[v];
    c /= double(fl.corners[i].size());
    if (c[0] > lo[0] && c[0] < hi[0] && c[1] > lo[1] && c[1] < hi[1]) {
      EXPECT_EQ(fl.corners[i].size(), 4u);
      ++quads_at_3_3;
    }
  }
  EXPECT_EQ(quads_at_3_3, 3);
  // quads (2,2) and (2,4) selected: quad (2,3) between them has two opposite hanging sides
  std::fill(sel.begin(), sel.end(), 0);
  sel[2 * 6 + 2] = sel[2 * 6 + 4] = 1;
  AdaptiveResult o = refine_selected(m, sel, 1);
  // 8 children; (2,3): 2 quads; 6 other edge neighbours: 2 quads + 1 triangle each; 27 unchanged
  EXPECT_EQ(o.mesh.quads.size(), 8u + 2 + 6 * 2 + 27);
  EXPECT_EQ(o.triangles.size(), 6u);
}

TEST(QuadSubAdaptive, SelectedRegionOfAClosedNetIsWatertightBalancedAndOnTheUniformSurface) {
  QuadMesh m = rounded_cube();
  auto in_region = [](const Point3& c) { return c[0] > 0.7 && c[1] > 0.4; };
  const std::vector<char> sel = select(m, in_region);
  Params p;
  p.iterations = 3;
  AdaptiveResult r = subdivide_adaptive(m.points, polygons(m), {}, sel, p, AdaptiveParams{});
  Result uniform = subdivide(m.points, polygons(m), {}, p);
  const Faces f = faces_of(r);

  // closed and conforming: each edge has exactly two faces, in opposite directions
  const auto edges = directed_edges(f);
  for (const auto& [e, face] : edges) EXPECT_TRUE(edges.count({e.second, e.first})) << "crack at " << e.first;
  std::set<int> used;
  for (const auto& c : f.corners) used.insert(c.begin(), c.end());
  EXPECT_EQ(used.size(), r.mesh.points.size());
  EXPECT_EQ(int(r.mesh.points.size()) - int(edges.size() / 2) + int(f.corners.size()), 2);  // sphere

  EXPECT_EQ(max_level_jump(f), 1);
  EXPECT_EQ(r.levels, 3);
  EXPECT_GT(r.triangles.size(), 0u);
  EXPECT_GT(r.balance_refinements, 0);  // level-2 faces at the region's rim force a ripple

  // interpolation: old vertices bit for bit; every new point is a point of the uniform scheme
  for (size_t i = 0; i < m.points.size(); ++i) EXPECT_EQ(r.mesh.points[i], m.points[i]);
  std::set<std::array<double, 3>> on_uniform;
  for (const auto& q : uniform.mesh.points) on_uniform.insert({q[0], q[1], q[2]});
  for (const auto& q : r.mesh.points) EXPECT_TRUE(on_uniform.count({q[0], q[1], q[2]}));

  // far from the region the input quads are untouched
  int far = 0;
  for (int q = 0; q < int(m.quads.size()); ++q) {
    const Point3 c = centroid(m, q);
    if (c[0] < 0.3) {
      EXPECT_TRUE(has_quad(r, m.quads[q]));
      ++far;
    }
  }
  EXPECT_GT(far, 20);
  // and everything selected reached level 3
  int selected = std::count(sel.begin(), sel.end(), 1);
  EXPECT_GE(r.refined_per_level[2], 16 * selected);
}

TEST(QuadSubAdaptive, ErrorThresholdRefinesWhereCurvatureIsHigh) {
  // two bumps of one width: a high one at (0.25, 0.25), five times lower at (0.75, 0.75)
  auto bumps = [](double x, double y) {
    auto g = [](double dx, double dy) { return std::exp(-(dx * dx + dy * dy) / (0.12 * 0.12)); };
    return 0.15 * g(x - 0.25, y - 0.25) + 0.03 * g(x - 0.75, y - 0.75);
  };
  QuadMesh m = grid(16, bumps);
  Params p;
  p.iterations = 2;
  AdaptiveParams by_error;
  by_error.refine = RefineFaces::ErrorAbove;
  by_error.error_threshold = 0.001;
  AdaptiveResult r = subdivide_adaptive(m.points, polygons(m), {}, {}, p, by_error);
  const Faces f = faces_of(r);
  EXPECT_EQ(max_level_jump(f), 1);
  std::map<std::string, std::vector<int>> faces_by_level;  // region -> count per level
  for (const char* region : {"high", "low", "flat"}) faces_by_level[region].assign(3, 0);
  for (size_t i = 0; i < f.corners.size(); ++i) {
    Point3 c(0, 0, 0);
    for (int v : f.corners[i]) c += r.mesh.points[v];
    c /= double(f.corners[i].size());
    if (std::hypot(c[0] - 0.25, c[1] - 0.25) < 0.3) ++faces_by_level["high"][f.level[i]];
    else if (std::hypot(c[0] - 0.75, c[1] - 0.75) < 0.3) ++faces_by_level["low"][f.level[i]];
    else if (std::hypot(c[0] - 1, c[1]) < 0.3 || std::hypot(c[0], c[1] - 1) < 0.3) ++faces_by_level["flat"][f.level[i]];
  }
  const auto& high = faces_by_level["high"];
  const auto& low = faces_by_level["low"];
  const auto& flat_corners = faces_by_level["flat"];
  EXPECT_GT(high[2], 0);                  // the high bump reaches level 2 ...
  EXPECT_EQ(low[2], 0);                   // ... the low one does not
  EXPECT_GT(high[1] + high[2], 2 * (low[1] + low[2]));
  EXPECT_EQ(flat_corners[1] + flat_corners[2], 0);  // flat corners stay coarse
  EXPECT_GT(flat_corners[0], 0);
  // a lower threshold refines more
  by_error.error_threshold = 0.0001;
  AdaptiveResult finer = subdivide_adaptive(m.points, polygons(m), {}, {}, p, by_error);
  EXPECT_GT(finer.mesh.quads.size(), r.mesh.quads.size());
}

// Every point of `r` is, bit for bit, a point of the uniform scheme `u`.
bool on_uniform_surface(const AdaptiveResult& r, const Result& u) {
  std::set<std::array<double, 3>> points;
  for (const auto& q : u.mesh.points) points.insert({q[0], q[1], q[2]});
  for (const auto& q : r.mesh.points)
    if (!points.count({q[0], q[1], q[2]})) return false;
  return true;
}

TEST(QuadSubAdaptive, OnlyTheRegionNearTheRefinementIsComputed) {
  QuadMesh m = rounded_cube(4);  // 1536 quads
  const std::vector<char> sel = select(m, [](const Point3& c) { return c[0] > 0.9 && c[1] > 0.9 && c[2] > 0.5; });
  Params p;
  p.iterations = 3;
  AdaptiveResult r = subdivide_adaptive(m.points, polygons(m), {}, sel, p, AdaptiveParams{});
  Result uniform = subdivide(m.points, polygons(m), {}, p);
  EXPECT_TRUE(on_uniform_surface(r, uniform));
  EXPECT_EQ(max_level_jump(faces_of(r)), 1);
  EXPECT_EQ(r.levels, 3);
  EXPECT_EQ(r.region_restarts, 0);
  // levels 0 and 1 in full, deeper levels only near the selection
  const int uniform_work = 1536 * (1 + 4 + 16 + 64);
  EXPECT_LT(r.hierarchy_faces, uniform_work / 3);  // measured 32800 of 130560
}

bool same_result(const AdaptiveResult& a, const AdaptiveResult& b) {
  return a.mesh.points == b.mesh.points && a.mesh.quads == b.mesh.quads && a.triangles == b.triangles &&
         a.quad_level == b.quad_level && a.triangle_level == b.triangle_level;
}

TEST(QuadSubAdaptive, WideningTheRegionDoesNotChangeTheResult) {
  auto bump = [](double x, double y) { return 0.2 * std::exp(-((x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5)) / 0.02); };
  QuadMesh m = grid(24, bump);
  Params p;
  p.iterations = 3;
  AdaptiveParams by_error;
  by_error.refine = RefineFaces::ErrorAbove;
  by_error.error_threshold = 0.0002;
  AdaptiveResult wide = subdivide_adaptive(m.points, polygons(m), {}, {}, p, by_error);
  by_error.initial_region_rings = 0;  // the ripple reaches past it: starts again wider
  AdaptiveResult narrow = subdivide_adaptive(m.points, polygons(m), {}, {}, p, by_error);
  EXPECT_GT(narrow.region_restarts, 0);
  EXPECT_TRUE(same_result(wide, narrow));
  Result uniform = subdivide(m.points, polygons(m), {}, p);
  EXPECT_TRUE(on_uniform_surface(narrow, uniform));
  EXPECT_EQ(narrow.levels, 3);
  EXPECT_LT(narrow.mesh.quads.size(), uniform.mesh.quads.size() / 2);
  // the same for a selection
  QuadMesh c = rounded_cube(3);
  const std::vector<char> sel = select(c, [](const Point3& q) { return q[0] > 0.8 && q[1] > 0.5; });
  AdaptiveParams selected, tight;
  tight.initial_region_rings = 0;
  AdaptiveResult a = subdivide_adaptive(c.points, polygons(c), {}, sel, p, selected);
  AdaptiveResult b = subdivide_adaptive(c.points, polygons(c), {}, sel, p, tight);
  EXPECT_GT(b.region_restarts, 0);
  EXPECT_TRUE(same_result(a, b));
}

TEST(QuadSubAdaptive, RegionsTouchingAtOneVertexAreNotMistakenForANonManifoldInput) {
  // The computed regions around two selected quads (5 rings each for 2 levels: 11 x 11 quads)
  // meet at the single grid vertex (12, 12) only; the step splits such a vertex in two, and
  // the points there lie outside the exact zone anyway.
  QuadMesh m = grid(24, [](double x, double y) { return 0.1 * std::sin(3 * x) * std::cos(2 * y); });
  std::vector<char> sel(m.quads.size(), 0);
  sel[6 * 24 + 6] = sel[17 * 24 + 17] = 1;
  Params p;
  p.iterations = 2;
  AdaptiveResult r = subdivide_adaptive(m.points, polygons(m), {}, sel, p, AdaptiveParams{});
  EXPECT_TRUE(on_uniform_surface(r, subdivide(m.points, polygons(m), {}, p)));
  EXPECT_EQ(r.refined_per_level[0], 10);  // 2 selected + their 8 edge neighbours (ripple)
  EXPECT_EQ(max_level_jump(faces_of(r)), 1);
}

TEST(QuadSubAdaptive, ACreaseThroughTheRefinedRegionStaysSharpAndConforming) {
  // a grid folded by 90 degrees along x = 0.5 (planes z = 0 and x = 0.5), crease marked
  const int n = 8;
  QuadMesh m = grid(n, flat);
  for (auto& q : m.points)
    if (q[0] > 0.5) { q[2] = q[0] - 0.5; q[0] = 0.5; }
  EdgeList crease;
  for (int j = 0; j < n; ++j) crease.push_back({j * (n + 1) + n / 2, (j + 1) * (n + 1) + n / 2});
  // select the quads on both sides of the fold in the lower half
  std::vector<char> sel(m.quads.size(), 0);
  for (int j = 0; j < n / 2; ++j) sel[j * n + n / 2 - 1] = sel[j * n + n / 2] = 1;
  Params p;
  p.iterations = 2;
  AdaptiveResult r = subdivide_adaptive(m.points, polygons(m), crease, sel, p, AdaptiveParams{});
  int off_planes = 0;
  for (const auto& q : r.mesh.points) off_planes += std::fabs(q[2]) > 1e-12 && std::fabs(q[0] - 0.5) > 1e-12;
  EXPECT_EQ(off_planes, 0);
  EXPECT_EQ(r.levels, 2);
  EXPECT_EQ(r.crease_edges_in, n);
  // conforming: an edge used by one face only lies on the grid's outer border
  const Faces f = faces_of(r);
  const auto edges = directed_edges(f);
  for (const auto& [e, face] : edges) {
    if (edges.count({e.second, e.first})) continue;
    const Point3 a = r.mesh.points[e.first], b = r.mesh.points[e.second];
    const bool on_border = (a[1] == 0 && b[1] == 0) || (a[1] == 1 && b[1] == 1) || (a[0] == 0 && b[0] == 0) ||
                           (a[2] == 0.5 && b[2] == 0.5);
    EXPECT_TRUE(on_border) << "crack between " << e.first << " and " << e.second;
  }
  EXPECT_EQ(max_level_jump(f), 1);
}

TEST(QuadSubAdaptive, BadAdaptiveInputIsRejected) {
  QuadMesh m = grid(3, flat);
  Params p;
  std::vector<char> none(m.quads.size(), 0);
  EXPECT_THROW(subdivide_adaptive(m.points, polygons(m), {}, none, p, AdaptiveParams{}), InvalidInput);
  EXPECT_THROW(subdivide_adaptive(m.points, polygons(m), {}, {1, 0}, p, AdaptiveParams{}), InvalidInput);
  AdaptiveParams by_error;
  by_error.refine = RefineFaces::ErrorAbove;
  by_error.error_threshold = 0;
  EXPECT_THROW(subdivide_adaptive(m.points, polygons(m), {}, {}, p, by_error), InvalidInput);
  AdaptiveParams bad_region;
  bad_region.initial_region_rings = -1;
  EXPECT_THROW(subdivide_adaptive(m.points, polygons(m), {}, {1, 0, 0, 0, 0, 0, 0, 0, 0}, p, bad_region), InvalidInput);
  // a flat mesh has no error: nothing is refined, the input comes back
  by_error.error_threshold = 0.01;
  AdaptiveResult r = subdivide_adaptive(m.points, polygons(m), {}, {}, p, by_error);
  EXPECT_EQ(r.mesh.quads.size(), m.quads.size());
  EXPECT_EQ(r.levels, 0);
}
