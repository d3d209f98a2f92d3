// Whole unions on synthetic bodies: closed, manifold, oriented, exact volumes.
#include "common/errors.h"
#include "shapes.h"
#include "union/surface_union.h"
#include "union_checks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace mr;
using namespace mr::surface_union;
using mr::test::make_body;
using mr::test::volume;
using mr::test::watertight;

namespace {

Result unite(const std::vector<Body>& bodies, double sliver = 10.0) {
  Params p;
  p.sliver_angle_deg = sliver;
  return compute_union(bodies, p);
}

void expect_closed(const Result& r) {
  const auto w = watertight(r);
  EXPECT_EQ(w.boundary_edges, 0);
  EXPECT_EQ(w.nonmanifold_edges, 0);
  EXPECT_EQ(w.misoriented_edges, 0);
}

Body cube_body(int n, double dx, double dy, double dz, double scale = 1) {
  TriMesh m;
  test::cube(m, n);
  return make_body(m, dx, dy, dz, scale);
}

}  // namespace

TEST(UnionCases, CubeAndCopyShiftedByHalfItsSize) {
  for (int n : {1, 3}) {
    const Result r = unite({cube_body(n, 0, 0, 0), cube_body(n, 1, 0, 0)});
    expect_closed(r);
    EXPECT_NEAR(volume(r), 12.0, 1e-12) << n;
    EXPECT_EQ(r.intersecting_pairs, 1);
    EXPECT_GT(r.intersection_edges, 0);
  }
}

TEST(UnionCases, CubeAndCopyShiftedDiagonally) {
  const Result r = unite({cube_body(2, 0, 0, 0), cube_body(2, 1, 1, 1)});
  expect_closed(r);
  EXPECT_NEAR(volume(r), 15.0, 1e-12);
}

TEST(UnionCases, TwoCubesSharingAFace) {
  const Result r = unite({cube_body(1, 0, 0, 0), cube_body(2, 2, 0, 0)});
  expect_closed(r);
  EXPECT_NEAR(volume(r), 16.0, 1e-12);
}

TEST(UnionCases, TwoCubesTouchingAlongAnEdgeStayManifold) {
  const Result r = unite({cube_body(1, 0, 0, 0), cube_body(1, 2, 2, 0)});
  expect_closed(r);
  EXPECT_NEAR(volume(r), 16.0, 1e-12);
}

TEST(UnionCases, SphereAndIdenticalCopy) {
  TriMesh m;
  test::sphere(m, 3);
  const Body a = make_body(m);
  const Result r = unite({a, a});
  expect_closed(r);
  EXPECT_NEAR(volume(r), volume(a), 1e-12);
  EXPECT_EQ(r.faces.size(), a.faces.size());
}

TEST(UnionCases, TwoOverlappingSpheres) {
  TriMesh m;
  test::sphere(m, 4);
  const Body a = make_body(m), b = make_body(m, 0.7, 0.2, 0.1);
  const Result r = unite({a, b});
  expect_closed(r);
  const double v = volume(r);
  EXPECT_GT(v, volume(a) * 1.3);
  EXPECT_LT(v, volume(a) * 2);
  EXPECT_EQ(r.lines.size(), 1u);
  EXPECT_TRUE(r.line_closed[0]);
}

TEST(UnionCases, NestedBodyIsRemoved) {
  const Result r = unite({cube_body(1, 0, 0, 0), cube_body(1, 0.1, 0, 0, 0.25)});
  expect_closed(r);
  EXPECT_NEAR(volume(r), 8.0, 1e-12);
  EXPECT_EQ(r.faces.size(), 12u);
}

TEST(UnionCases, DisjointBodiesAreBothKept) {
  const Result r = unite({cube_body(1, 0, 0, 0), cube_body(1, 5, 0, 0)});
  expect_closed(r);
  EXPECT_NEAR(volume(r), 16.0, 1e-12);
}

TEST(UnionCases, SphereAndCylinder) {
  TriMesh s, c;
  test::sphere(s, 4);
  test::cylinder(c, 64, 8, 0.4, 3.0);
  const Result r = unite({make_body(s), make_body(c, 0.1, 0.05, 0)});
  expect_closed(r);
  EXPECT_EQ(r.lines.size(), 2u);
}

TEST(UnionBadInput, MessagesNameTheBody) {
  Body open = cube_body(1, 0, 0, 0);
  open.faces.pop_back();
  open.name = "lid";
  try {
    compute_union({cube_body(1, 0, 0, 0), open});
    FAIL();
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("body 1 ('lid') is not closed"), std::string::npos) << e.what();
  }
  Body nan = cube_body(1, 0, 0, 0);
  nan.vertices[0][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(compute_union({nan}), InvalidInput);
  EXPECT_THROW(compute_union({}), InvalidInput);
  EXPECT_THROW(compute_union({Body{}}), InvalidInput);
}
