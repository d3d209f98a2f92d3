// Where the union's faces and vertices lie on the input (source_attributes.h): every face
// in its source face, every vertex at its barycentric point there, through the cut, the
// splits and merges, and the sliver step's moves.
#include "common/closest_point.h"
#include "common/errors.h"
#include "shapes.h"
#include "union/exact.h"
#include "union/source_attributes.h"
#include "union_checks.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace mr;
using namespace mr::surface_union;

namespace {

Body shape(void (*make)(TriMesh&, int), int n, double dx, double dy, double dz, double scale) {
  TriMesh m;
  make(m, n);
  return test::make_body(m, dx, dy, dz, scale);
}

std::vector<Body> two_cubes() {
  return {shape(test::cube, 2, 0, 0, 0, 1), shape(test::cube, 3, 0.5, 0.3, 0.2, 1)};
}

std::vector<Body> three_spheres() {
  return {shape(test::sphere, 3, 0, 0, 0, 1), shape(test::sphere, 3, 0.9, 0.2, 0.1, 0.7),
          shape(test::sphere, 2, 0.3, 0.8, -0.2, 0.5)};
}

const std::array<double, 3>& corner(const std::vector<Body>& bodies, const FaceOrigin& o, int z) {
  const Body& b = bodies[size_t(o.body)];
  return b.vertices[size_t(b.faces[size_t(o.face)][size_t(z)])];
}

double distance_to_source(const std::vector<Body>& bodies, const FaceOrigin& o, const std::array<double, 3>& p) {
  std::array<double, 3> bary{};
  auto pt = [&](int z) { return Point3(corner(bodies, o, z)[0], corner(bodies, o, z)[1], corner(bodies, o, z)[2]); };
  const Point3 q = closest_point_on_triangle(Point3(p[0], p[1], p[2]), pt(0), pt(1), pt(2), bary);
  return (q - Point3(p[0], p[1], p[2])).Norm();
}

double diagonal(const Result& r) {
  std::array<double, 3> lo = r.vertices[0], hi = lo;
  for (const auto& p : r.vertices)
    for (int k = 0; k < 3; ++k) { lo[k] = std::min(lo[k], p[k]); hi[k] = std::max(hi[k], p[k]); }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

Result unite(const std::vector<Body>& bodies, double sliver) {
  Params p;
  p.sliver_angle_deg = sliver;
  return compute_union(bodies, p);
}

}  // namespace

TEST(SourceAttributes, EveryFaceOfTheExactArrangementLiesInItsSourceFacesPlane) {
  for (const auto& bodies : {two_cubes(), three_spheres()}) {
    const Result r = unite(bodies, 0);
    ASSERT_EQ(r.face_source.size(), r.faces.size());
    const auto faces = face_origins(r, bodies);
    const auto body = face_bodies(r, bodies);
    int off_plane = 0, bodies_seen = 0;
    std::vector<char> seen(bodies.size(), 0);
    for (size_t f = 0; f < faces.size(); ++f) {
      ASSERT_GE(faces[f].body, 0);
      ASSERT_LT(faces[f].body, int(bodies.size()));
      EXPECT_EQ(body[f], faces[f].body);
      for (int v : r.faces[f])  // rounded intersection points lie within rounding of the plane
        if (distance_to_source(bodies, faces[f], r.vertices[size_t(v)]) > 1e-12) ++off_plane;
      if (!seen[size_t(faces[f].body)]) ++bodies_seen;
      seen[size_t(faces[f].body)] = 1;
    }
    EXPECT_EQ(off_plane, 0);
    EXPECT_EQ(bodies_seen, int(bodies.size()));
  }
}

TEST(SourceAttributes, VerticesAreTheirBarycentricPointsAndInputVerticesKeepTheirOwn) {
  for (const auto& bodies : {two_cubes(), three_spheres()}) {
    const Result r = unite(bodies, 0);
    const auto points = vertex_origins(r, bodies);
    ASSERT_EQ(points.size(), r.vertices.size());
    int input_vertices = 0;
    for (size_t v = 0; v < points.size(); ++v) {
      const auto& w = points[v].weight;
      EXPECT_NEAR(w[0] + w[1] + w[2], 1.0, 1e-12);
      std::array<double, 3> p{0, 0, 0};
      for (int z = 0; z < 3; ++z) {
        EXPECT_GE(w[size_t(z)], 0.0);
        for (int k = 0; k < 3; ++k) p[size_t(k)] += w[size_t(z)] * corner(bodies, points[v].face, z)[size_t(k)];
        if (w[size_t(z)] == 1.0) {
          EXPECT_EQ(corner(bodies, points[v].face, z), r.vertices[v]);  // exactly the input vertex
          ++input_vertices;
        }
      }
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[size_t(k)], r.vertices[v][size_t(k)], 1e-12);
    }
    EXPECT_GT(input_vertices, 0);
    EXPECT_LT(input_vertices, int(points.size()));  // the intersection points are not
  }
}

TEST(SourceAttributes, AfterTheSliverStepFacesStayWithinItsDeviationBoundOfTheirSourceBody) {
  // A vertex removed on an intersection line refills faces on both sides of the line: each
  // new face must take a source on its own side (its own body), which this would catch:
  // the other body's faces are far away. A line vertex may have moved onto one body's
  // crease: it is then measured on that body.
  for (const auto& bodies : {two_cubes(), three_spheres()}) {
    const Params defaults;
    const Result r = unite(bodies, defaults.sliver_angle_deg);
    ASSERT_GT(r.slivers_collapsed, 0);
    ASSERT_EQ(r.face_source.size(), r.faces.size());
    const double bound = defaults.sliver_max_deviation * diagonal(r) + 1e-12;
    const auto faces = face_origins(r, bodies);
    double worst = 0;
    for (size_t f = 0; f < faces.size(); ++f) {
      std::array<double, 3> g{0, 0, 0};
      for (int v : r.faces[f])
        for (int k = 0; k < 3; ++k) g[size_t(k)] += r.vertices[size_t(v)][size_t(k)] / 3;
      // Its centroid lies within the bound of the cut's surface, which lies in the sources;
      // the face's origin is the nearest face of its body to it.
      const double d = distance_to_source(bodies, faces[f], g);
      worst = std::max(worst, d);
    }
    EXPECT_LE(worst, bound);
    const auto points = vertex_origins(r, bodies);
    for (size_t v = 0; v < points.size(); ++v) {
      std::array<double, 3> p{0, 0, 0};
      for (int z = 0; z < 3; ++z)
        for (int k = 0; k < 3; ++k) p[size_t(k)] += points[v].weight[size_t(z)] * corner(bodies, points[v].face, z)[size_t(k)];
      const double d = std::sqrt((p[0] - r.vertices[v][0]) * (p[0] - r.vertices[v][0]) +
                                 (p[1] - r.vertices[v][1]) * (p[1] - r.vertices[v][1]) +
                                 (p[2] - r.vertices[v][2]) * (p[2] - r.vertices[v][2]));
      EXPECT_LE(d, bound) << "vertex " << v;
    }
  }
}

TEST(SourceAttributes, AResultWithoutSourcesIsRefused) {
  const auto bodies = two_cubes();
  Result r = unite(bodies, 0);
  r.face_source.pop_back();
  EXPECT_THROW(face_origins(r, bodies), InvalidInput);
}
