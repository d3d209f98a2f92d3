// Whole remesh runs on synthetic shapes: topology, corners, angles.
#include "common/errors.h"
#include "remesh/remesh.h"
#include "shapes.h"

#include <vcg/complex/append.h>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

using namespace mr;

namespace {

struct Topology {
  int boundary_edges = 0, non_manifold_edges = 0, misoriented_edges = 0, euler = 0;
};

Topology topology(const TriMesh& m) {
  std::map<std::pair<int, int>, int> directed;
  std::map<std::pair<int, int>, int> undirected;
  for (const auto& f : m.face)
    for (int z = 0; z < 3; ++z) {
      int a = int(vcg::tri::Index(m, f.cV(z))), b = int(vcg::tri::Index(m, f.cV((z + 1) % 3)));
      directed[{a, b}]++;
      undirected[std::minmax(a, b)]++;
    }
  Topology t;
  for (const auto& [e, n] : undirected) {
    if (n == 1) t.boundary_edges++;
    if (n > 2) t.non_manifold_edges++;
  }
  for (const auto& [e, n] : directed)
    if (n > 1) t.misoriented_edges++;
  t.euler = int(m.vert.size()) - int(undirected.size()) + int(m.face.size());
  return t;
}

struct RemeshRun {
  remesh::Result r;
  TriMesh mesh;
};

void run(const TriMesh& m, double h, RemeshRun& out, remesh::Recovery rec = remesh::Recovery::Linear) {
  remesh::Params p;
  p.target_length = h;
  p.recovery = rec;
  out.r = remesh::remesh(m, p, out.mesh);
}

void run(const TriMesh& m, double h) {
  RemeshRun out;
  run(m, h, out);
}

}  // namespace

TEST(RemeshWhole, CubeIsClosedManifoldKeepsCornersAndAngles) {
  TriMesh m;
  test::cube(m, 1);
  RemeshRun run_;
  run(m, 0.2, run_);
  const auto& r = run_.r;
  const TriMesh& out = run_.mesh;
  const Topology t = topology(out);
  EXPECT_EQ(r.unmeshed_sides, 0);
  EXPECT_EQ(t.boundary_edges, 0);
  EXPECT_EQ(t.non_manifold_edges, 0);
  EXPECT_EQ(t.misoriented_edges, 0);
  EXPECT_EQ(t.euler, 2);
  // Every cube corner is an output vertex at the same position.
  for (int x : {-1, 1})
    for (int y : {-1, 1})
      for (int z : {-1, 1}) {
        double best = 1e9;
        for (const auto& v : out.vert) best = std::min(best, (v.cP() - Point3(x, y, z)).Norm());
        EXPECT_EQ(best, 0.0);
      }
  // 12 edges of length 2 at h=0.2: 10 segments each.
  EXPECT_EQ(r.feature_edges, 120);
  EXPECT_GE(r.min_angle_deg, 30.0);
  EXPECT_GE(r.edges_in_range, 0.95);
  // All points lie on the cube.
  for (const auto& v : out.vert) {
    const double linf = std::max({std::abs(v.cP()[0]), std::abs(v.cP()[1]), std::abs(v.cP()[2])});
    EXPECT_NEAR(linf, 1.0, 1e-9);
  }
}

TEST(RemeshWhole, SphereWithoutFeaturesIsClosed) {
  TriMesh m;
  test::sphere(m, 4);
  RemeshRun run_;
  run(m, 0.15, run_);
  const auto& r = run_.r;
  const TriMesh& out = run_.mesh;
  const Topology t = topology(out);
  EXPECT_EQ(r.unmeshed_sides, 0);
  EXPECT_EQ(r.corners, 0);
  EXPECT_EQ(t.boundary_edges, 0);
  EXPECT_EQ(t.non_manifold_edges, 0);
  EXPECT_EQ(t.misoriented_edges, 0);
  EXPECT_EQ(t.euler, 2);
  EXPECT_GE(r.min_angle_deg, 25.0);
  EXPECT_GE(r.mean_min_angle_deg, 50.0);
  EXPECT_LT(r.hausdorff, 0.02);
}

TEST(RemeshWhole, BadInputThrows) {
  TriMesh empty;
  EXPECT_THROW(run(empty, 0.1), InvalidInput);
  TriMesh m;
  test::cube(m, 1);
  EXPECT_THROW(run(m, 0.0), InvalidInput);
  EXPECT_THROW(run(m, -1.0), InvalidInput);
  EXPECT_THROW(run(m, 10.0), InvalidInput);  // diagonal is about 3.46
  // Every face degenerate (all corners on one line): no surface to remesh.
  for (auto& v : m.vert) v.P() = Point3(v.P()[0] + v.P()[1] + v.P()[2], 0, 0);
  EXPECT_THROW(run(m, 0.5), InvalidInput);
}

TEST(RemeshWhole, PeakSharperThanTheElementsGetsAnOutputVertexAtItsTip) {
  // A 1 x 1 grid of spacing 0.05 with a cone of radius 0.3 and height 0.15 in the middle (no
  // ridge at 70 degrees): elements of 0.25 would cut its tip off; a free point moves onto it.
  TriMesh m;
  test::grid(m, 20);
  const Point3 tip(0.5, 0.5, 0.15);
  for (auto& v : m.vert) {
    const double r = (v.P() - Point3(0.5, 0.5, 0)).Norm();
    v.P()[2] = 0.15 * std::max(0.0, 1.0 - r / 0.3);
  }
  remesh::Params p;
  p.target_length = 0.25;
  p.ridge_angle_deg = 70;
  TriMesh out;
  const remesh::Result r = remesh::remesh(m, p, out);
  EXPECT_EQ(r.unmeshed_sides, 0);
  EXPECT_GE(r.snapped, 1);
  double closest = 1e9;
  for (const auto& v : out.vert) closest = std::min(closest, (v.cP() - tip).Norm());
  EXPECT_LE(closest, 1e-12);
  EXPECT_GE(r.min_angle_deg, 10.0);
}

TEST(RemeshWhole, ThinPlateRimsGetStaggeredPointsAcrossTheirStrips) {
  // A 100 x 50 x 0.1 plate at size 2: each rim is one layer of faces between two ridges. Points
  // across a rim right opposite each other would give right triangles of atan(0.1 / 2) = 2.9
  // degrees; staggered by 0.28 of a segment the worst is atan(0.1 / (0.72 x 2)) = 4.0 degrees.
  TriMesh m;
  test::cube(m, 1);
  for (auto& v : m.vert) v.P() = Point3(v.P()[0] * 50.0, v.P()[1] * 25.0, v.P()[2] * 0.05);
  RemeshRun run_;
  run(m, 2.0, run_);
  const Topology t = topology(run_.mesh);
  EXPECT_EQ(run_.r.unmeshed_sides, 0);
  EXPECT_EQ(run_.r.thin_patches, 4);
  EXPECT_EQ(t.boundary_edges, 0);
  EXPECT_EQ(t.non_manifold_edges, 0);
  EXPECT_EQ(t.misoriented_edges, 0);
  EXPECT_EQ(t.euler, 2);
  EXPECT_GE(run_.r.min_angle_deg, 3.9);
}

TEST(RemeshWhole, ShapesFarFromTheOriginStayClosedAndKeepTheirCornersBitForBit) {
  // Far from the origin (here 1e6-1e7 sizes away, as in UTM coordinates) the core shifts the
  // input next to the origin, exactly, and back: the cube's corners are its input vertices
  // bit for bit (the regression on a real model, fandisk, is in test_remesh.py).
  TriMesh cube, cylinder;
  test::cube(cube, 2);
  test::cylinder(cylinder, 48, 12, 1.0, 3.0);
  const Point3 far(3.1e6 + 0.37, -2.7e7 - 0.61, 1.9e6 + 0.23);
  for (TriMesh* shape : {&cube, &cylinder}) {
    TriMesh moved;
    vcg::tri::Append<TriMesh, TriMesh>::MeshCopyConst(moved, *shape);
    for (auto& v : moved.vert) v.P() += far;  // rounded: the far cube is no longer exactly flat
    RemeshRun far_run;
    run(moved, 0.1, far_run);
    EXPECT_EQ(far_run.r.unmeshed_sides, 0);
    EXPECT_EQ(far_run.r.retried_patches, 0);
    const Topology t = topology(far_run.mesh);
    EXPECT_EQ(t.boundary_edges, 0);
    EXPECT_EQ(t.non_manifold_edges, 0);
    EXPECT_EQ(t.misoriented_edges, 0);
    EXPECT_EQ(t.euler, 2);
    EXPECT_GE(far_run.r.min_angle_deg, 28.0);  // 39.1 and 42.6 near the origin, 30.8 and 32.7 here
    int corners = 0;
    for (const auto& v : far_run.mesh.vert)
      if (v.IsS()) {
        ++corners;
        bool found = false;
        for (const auto& w : moved.vert) found = found || w.cP() == v.cP();
        EXPECT_TRUE(found);
      }
    EXPECT_EQ(corners, shape == &cube ? 8 : 0);
  }
}
