// Unit tests of the patch-gap healing core on a cube whose six faces are
// triangulated separately: T-junctions, gaps, overlaps, flipped patches.
#include "common/errors.h"
#include "healing/patch_cases.h"
#include "healing/patch_healing.h"
#include "shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace mr;

namespace {

healing::Params with_tolerance(double tol) {
  healing::Params p;
  p.vertex_tolerance = tol;
  return p;
}

healing::Result heal_box(const test::BoxPatches& spec, double tol) {
  TriMesh m;
  std::vector<int> patches;
  test::box_patches(m, patches, spec);
  return healing::heal(m, patches, with_tolerance(tol));
}

/// The healed surface as a mesh, for the measurements.
struct Healed {
  TriMesh mesh;
  explicit Healed(const healing::Result& r) { test::build(mesh, r.points, r.faces); }
};

}  // namespace

TEST(PatchHealing, TJunctionsOnlyBoxBecomesClosedWithoutMoving) {
  test::BoxPatches spec;  // six faces at 2..5 squares per side: T-junctions on every cube edge
  const auto r = heal_box(spec, 1e-3);
  EXPECT_EQ(r.patches_in, 6);
  EXPECT_GT(r.boundary_edges_before, 0);
  EXPECT_GT(r.t_junctions_split, 0);
  EXPECT_EQ(r.boundary_edges_after, 0);
  EXPECT_EQ(test::boundary_edge_count(Healed(r).mesh), 0);
  EXPECT_EQ(test::non_manifold_edge_count(Healed(r).mesh), 0);
  EXPECT_TRUE(test::consistently_oriented(Healed(r).mesh));
  EXPECT_NEAR(test::signed_volume(Healed(r).mesh), 8.0, 1e-9);
  EXPECT_LE(r.largest_move, 1e-12);  // the faces already touched: nothing moves
}

TEST(PatchHealing, GapsBelowToleranceCloseAndMovesStayWithinTolerance) {
  test::BoxPatches spec;
  spec.offset = 0.005;  // neighbouring faces about 0.007 apart along every cube edge
  const double tol = 0.02;
  const auto r = heal_box(spec, tol);
  EXPECT_EQ(r.boundary_edges_after, 0);
  EXPECT_EQ(test::non_manifold_edge_count(Healed(r).mesh), 0);
  EXPECT_TRUE(test::consistently_oriented(Healed(r).mesh));
  EXPECT_GT(r.vertices_moved, 0);
  EXPECT_LE(r.largest_move, tol);
  EXPECT_NEAR(test::signed_volume(Healed(r).mesh), 8.0, 0.2);  // the cube grew by about 0.005 per face
  for (const auto& p : r.points)  // every vertex stays within the offset shell
    EXPECT_LE(std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])}), 1.005 + 1e-12);
}

TEST(PatchHealing, GapsAboveToleranceStayOpenAndAreReported) {
  test::BoxPatches spec;
  spec.offset = 0.05;  // gaps about 0.07 wide
  const double tol = 0.02;
  const auto r = heal_box(spec, tol);
  EXPECT_EQ(r.borders_paired, 0);
  EXPECT_EQ(r.boundary_edges_after, r.boundary_edges_before);
  EXPECT_EQ(r.open_loops, 6);
  EXPECT_GT(r.gaps_left, 0);
  EXPECT_NEAR(r.largest_gap, 0.05 * std::sqrt(2.0), 0.02);
  EXPECT_EQ(r.largest_move, 0);
}

TEST(PatchHealing, EdgeToleranceRejectsPairsThatAreTooFarApart) {
  test::BoxPatches spec;
  spec.resolution = {2, 2, 2, 2, 2, 2};  // matching vertices: pairing by vertices only
  spec.offset = 0.01;                    // seams about 0.014 apart
  TriMesh m;
  std::vector<int> patches;
  test::box_patches(m, patches, spec);
  healing::Params p = with_tolerance(0.02);
  p.edge_tolerance = 0.005;
  const auto r = healing::heal(m, patches, p);
  EXPECT_EQ(r.borders_paired, 0);
  EXPECT_GT(r.pairs_rejected, 0);
  EXPECT_EQ(r.boundary_edges_after, r.boundary_edges_before);
}

TEST(PatchHealing, OverlapsWithinToleranceAreTrimmedToOneSeam) {
  test::BoxPatches spec;
  spec.resolution = {3, 3, 3, 3, 3, 3};
  spec.overlap = 0.004;  // each face reaches 0.004 past the cube edges
  const double tol = 0.02;
  const auto r = heal_box(spec, tol);
  EXPECT_EQ(r.boundary_edges_after, 0);
  EXPECT_EQ(test::non_manifold_edge_count(Healed(r).mesh), 0);
  EXPECT_TRUE(test::consistently_oriented(Healed(r).mesh));
  EXPECT_LE(r.largest_move, tol);
}

TEST(PatchHealing, FlippedPatchesEndOutward) {
  test::BoxPatches spec;
  spec.flip = {false, true, false, true, true, false};
  const auto r = heal_box(spec, 1e-3);
  EXPECT_EQ(r.boundary_edges_after, 0);
  EXPECT_TRUE(test::consistently_oriented(Healed(r).mesh));
  EXPECT_GT(r.faces_flipped, 0);
  EXPECT_EQ(r.orientation_conflicts, 0);
  EXPECT_NEAR(test::signed_volume(Healed(r).mesh), 8.0, 1e-9);
}

TEST(PatchHealing, FlippedPatchesFarFromTheOriginEndOutward) {
  // Far from the origin the signed volume about it cancels to noise and chose the
  // orientation at random; it is now taken about a vertex of the part.
  test::BoxPatches spec;
  spec.flip = {true, true, false, true, true, false};
  TriMesh m;
  std::vector<int> patches;
  test::box_patches(m, patches, spec);
  const Point3 far(3.3e7 + 0.37, -2.1e7 + 0.61, 1.7e7 + 0.23);
  for (auto& v : m.vert) v.P() += far;
  const auto r = healing::heal(m, patches, with_tolerance(1e-3));
  Healed healed(r);
  for (auto& v : healed.mesh.vert) v.P() -= far;
  EXPECT_EQ(r.boundary_edges_after, 0);
  EXPECT_EQ(r.orientation_conflicts, 0);
  EXPECT_NEAR(test::signed_volume(healed.mesh), 8.0, 1e-6);
}

TEST(PatchHealing, CubeSeamsAreFeaturesAndFacesGroupBySide) {
  // A closed cube split along its 12 edges and along a flat seam in the middle
  // of every face: 12 patches, 6 groups, the 12 cube edges as feature lines.
  TriMesh cube;
  test::cube(cube, 4);
  std::vector<int> patches(cube.face.size());
  for (size_t f = 0; f < cube.face.size(); ++f) {
    const Point3 c = (cube.face[f].cP(0) + cube.face[f].cP(1) + cube.face[f].cP(2)) / 3.0;
    const Point3 n = vcg::NormalizedTriangleNormal(cube.face[f]);
    int axis = 0;
    for (int k = 1; k < 3; ++k) if (std::abs(n[k]) > std::abs(n[axis])) axis = k;
    const int side = n[axis] > 0 ? 0 : 1;
    const int half = c[(axis + 1) % 3] > 0 ? 1 : 0;
    patches[f] = 4 * axis + 2 * side + half;
  }
  const auto r = healing::heal(cube, patches, with_tolerance(1e-3));
  EXPECT_EQ(r.patches_in, 12);
  EXPECT_EQ(r.groups, 6);
  EXPECT_EQ(r.feature_edges, 12 * 4);  // 4 mesh edges along each cube edge
  EXPECT_EQ(r.boundary_edges_after, 0);
  EXPECT_EQ(r.largest_move, 0);
}

TEST(PatchHealing, DuplicatedSeamVerticesWeldBackToTheOriginal) {
  // The cube with every face's vertices duplicated: welding restores it exactly.
  TriMesh cube;
  test::cube(cube, 3);
  std::vector<Point3> points;
  std::vector<std::array<int, 3>> faces;
  for (const auto& f : cube.face) {
    for (int z = 0; z < 3; ++z) points.push_back(f.cP(z));
    faces.push_back({int(points.size()) - 3, int(points.size()) - 2, int(points.size()) - 1});
  }
  TriMesh soup;
  test::build(soup, points, faces);
  const auto r = healing::heal(soup, {}, with_tolerance(1e-6));
  EXPECT_EQ(r.patches_in, int(cube.face.size()));  // every triangle its own component
  EXPECT_EQ(int(r.points.size()), int(cube.vert.size()));
  EXPECT_EQ(r.boundary_edges_after, 0);
  EXPECT_EQ(r.largest_move, 0);
  EXPECT_TRUE(test::consistently_oriented(Healed(r).mesh));
}

TEST(PatchHealing, SameInputGivesTheSameOutput) {
  test::BoxPatches spec;
  spec.offset = 0.004;
  const auto a = heal_box(spec, 0.02), b = heal_box(spec, 0.02);
  ASSERT_EQ(a.points.size(), b.points.size());
  ASSERT_EQ(a.faces.size(), b.faces.size());
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.faces, b.faces);
}

TEST(PatchHealing, BadInputIsRejectedWithAClearMessage) {
  TriMesh empty;
  EXPECT_THROW(healing::heal(empty, {}, with_tolerance(0.01)), InvalidInput);
  TriMesh cube;
  test::cube(cube, 1);
  EXPECT_THROW(healing::heal(cube, {}, with_tolerance(0)), InvalidInput);
  EXPECT_THROW(healing::heal(cube, {}, with_tolerance(-1)), InvalidInput);
  EXPECT_THROW(healing::heal(cube, {}, with_tolerance(std::numeric_limits<double>::quiet_NaN())), InvalidInput);
  EXPECT_THROW(healing::heal(cube, {1, 2}, with_tolerance(0.01)), InvalidInput);
  healing::Params p = with_tolerance(0.01);
  p.feature_angle_deg = 200;
  EXPECT_THROW(healing::heal(cube, {}, p), InvalidInput);
  cube.vert[0].P()[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(healing::heal(cube, {}, with_tolerance(0.01)), InvalidInput);
}

TEST(PatchHealing, LongBorderEdgesAgainstATinyToleranceStayCheap) {
  // Found by fuzzing (fuzz_filters.py seed 863): 30 triangles of random points in the unit
  // cube, tolerance 1e-4 of the diagonal. Each open edge's whole box went into a grid of
  // tolerance-sized cells (millions of cells per edge: 298 s); segments are now filed in
  // pieces of a cell. The soup has nothing to heal: every edge stays open, no pair, no move.
  std::vector<Point3> points;
  std::vector<std::array<int, 3>> faces;
  uint32_t state = 863;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) / double(1u << 24);
  };
  for (int f = 0; f < 30; ++f) {
    for (int k = 0; k < 3; ++k) points.emplace_back(next(), next(), next());
    faces.push_back({3 * f, 3 * f + 1, 3 * f + 2});
  }
  healing::Params p;
  p.vertex_tolerance = 1.7e-4;
  p.edge_tolerance = 1.7e-3;
  const auto r = healing::heal(points, faces, {}, p);
  EXPECT_EQ(r.faces.size(), 30u);
  EXPECT_EQ(r.borders_paired, 0);
  EXPECT_EQ(r.vertices_moved, 0);
  EXPECT_EQ(r.boundary_edges_after, 90);
}
