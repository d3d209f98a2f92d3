// Edges whose two ends round to one place: merged, so that no output face degenerates.
#include "shapes.h"
#include "union/rounded_edges.h"
#include "union/self_intersection.h"
#include "union/surface_union.h"
#include "union_checks.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace mr;
using namespace mr::surface_union;

namespace {

/// Faces with two corners at one place.
int faces_with_coincident_corners(const Result& r) {
  int n = 0;
  for (const auto& t : r.faces)
    for (int z = 0; z < 3; ++z)
      if (r.vertices[size_t(t[size_t(z)])] == r.vertices[size_t(t[size_t((z + 1) % 3)])]) {
        ++n;
        break;
      }
  return n;
}

/// An octahedron whose apex is two vertices at one place (5 and 6), joined by an edge whose
/// two faces have no area: (5, 2, 6) and (6, 0, 5). Side (2 -> 5) of face (5, 1, 2) is flagged
/// as a line edge; the side it becomes one with after the merge, (6 -> 2) of (6, 2, 3), is not.
Result octahedron_with_split_apex() {
  Result r;
  r.vertices = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}, {0, 0, 1}, {0, 0, 1}};
  r.faces = {{5, 0, 1}, {5, 1, 2}, {5, 2, 6}, {6, 2, 3}, {6, 3, 0}, {6, 0, 5},
             {4, 1, 0}, {4, 2, 1}, {4, 3, 2}, {4, 0, 3}};
  r.line_edge.assign(r.faces.size(), {false, false, false});
  r.line_edge[1][2] = true;
  return r;
}

}  // namespace

TEST(RoundedEdges, SplitApexMergesBackIntoTheOctahedron) {
  Result r = octahedron_with_split_apex();
  ASSERT_EQ(mr::test::watertight(r).ok(), true);
  ASSERT_EQ(faces_with_coincident_corners(r), 2);
  const double volume = mr::test::volume(r);
  std::vector<char> cut(r.faces.size(), 1);
  EXPECT_EQ(merge_rounded_together(r, cut), 1);
  EXPECT_EQ(r.faces.size(), 8u);
  EXPECT_EQ(r.vertices.size(), 6u);
  EXPECT_EQ(cut.size(), 8u);
  EXPECT_EQ(r.line_edge.size(), 8u);
  EXPECT_TRUE(mr::test::watertight(r).ok());
  EXPECT_EQ(faces_with_coincident_corners(r), 0);
  EXPECT_DOUBLE_EQ(mr::test::volume(r), volume);
  // The line edge from the apex to (-1, 0, 0) is flagged on both of its faces now.
  int apex = -1, left = -1;
  for (int v = 0; v < int(r.vertices.size()); ++v) {
    if (r.vertices[size_t(v)] == std::array<double, 3>{0, 0, 1}) apex = v;
    if (r.vertices[size_t(v)] == std::array<double, 3>{-1, 0, 0}) left = v;
  }
  int flagged = 0, others = 0;
  for (size_t f = 0; f < r.faces.size(); ++f)
    for (int z = 0; z < 3; ++z) {
      const int u = r.faces[f][size_t(z)], w = r.faces[f][size_t((z + 1) % 3)];
      const bool on = (u == apex && w == left) || (u == left && w == apex);
      (on ? flagged : others) += r.line_edge[f][size_t(z)] ? 1 : 0;
    }
  EXPECT_EQ(flagged, 2);
  EXPECT_EQ(others, 0);
}

// The apex as a tiny face (three vertices a unit in the last place apart, each joined to
// the others): the three are one cluster and go at once; the faces that move (by a unit)
// are checked first.
TEST(RoundedEdges, ATinyFaceOfThreeCloseCornersGoesAsAWhole) {
  const double u = std::nextafter(1.0, 2.0) - 1.0;
  Result r;
  r.vertices = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}, {0, 0, 1}, {u, 0, 1}, {0, u, 1}};
  r.faces = {{5, 0, 1}, {5, 1, 6}, {6, 1, 2}, {6, 2, 7}, {7, 2, 3}, {7, 3, 0}, {7, 0, 5}, {5, 6, 7},
             {4, 1, 0}, {4, 2, 1}, {4, 3, 2}, {4, 0, 3}};
  r.line_edge.assign(r.faces.size(), {false, false, false});
  ASSERT_TRUE(mr::test::watertight(r).ok());
  std::vector<char> cut(r.faces.size(), 1);
  EXPECT_EQ(merge_rounded_together(r, cut), 2);
  EXPECT_EQ(r.faces.size(), 8u);
  EXPECT_EQ(r.vertices.size(), 6u);
  EXPECT_TRUE(mr::test::watertight(r).ok());
  Body out;
  out.name = "result";
  out.vertices = r.vertices;
  out.faces = r.faces;
  EXPECT_FALSE(self_intersection(out).has_value());
  EXPECT_NEAR(mr::test::volume(r), 4.0 / 3.0, 1e-12);
}

TEST(RoundedEdges, OnlyCutFacesAreLookedAtAndDistinctEndsStay) {
  Result r = octahedron_with_split_apex();
  std::vector<char> cut(r.faces.size(), 0);  // no cut face: no crossing, nothing to merge
  EXPECT_EQ(merge_rounded_together(r, cut), 0);
  EXPECT_EQ(r.faces.size(), 10u);
  TriMesh m;
  test::sphere(m, 2);
  const Body b = mr::test::make_body(m);
  Result s;
  s.vertices = b.vertices;
  s.faces = b.faces;
  s.line_edge.assign(s.faces.size(), {false, false, false});
  std::vector<char> all(s.faces.size(), 1);
  EXPECT_EQ(merge_rounded_together(s, all), 0);
  EXPECT_EQ(s.faces, b.faces);
}

// A sphere and its copy turned by a floating-point half turn about an axis of symmetry:
// the copy's vertices lie within a few units in the last place of the sphere's, and
// crossings of the two sheets closer than that round to one place.
TEST(RoundedEdges, NearlyCoincidentSpheresGiveNoFaceWithCoincidentCorners) {
  TriMesh m;
  test::sphere(m, 3);
  Body a = mr::test::make_body(m), b = a;
  const double c = std::cos(M_PI), s = std::sin(M_PI);
  for (auto& p : b.vertices) p = {p[0], c * p[1] - s * p[2], s * p[1] + c * p[2]};
  for (const double sliver : {0.0, 10.0}) {
    Params prm;
    prm.sliver_angle_deg = sliver;
    const Result r = compute_union({a, b}, prm);
    EXPECT_GT(r.rounded_edges_merged, 0) << sliver;
    EXPECT_EQ(faces_with_coincident_corners(r), 0) << sliver;
    EXPECT_TRUE(mr::test::watertight(r).ok()) << sliver;
    EXPECT_NEAR(mr::test::volume(r), mr::test::volume(a), 1e-6 * mr::test::volume(a)) << sliver;
  }
}
