// Corners joined by a line much shorter than the elements share one output point.
#include "remesh/remesh.h"
#include "shapes.h"

#include <vcg/complex/complex.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

using namespace mr;

namespace {

// The cube [-1,1]^3 with its corner (1,1,1) cut off by a triangle of side cut x sqrt(2): three
// corners joined by three tiny lines around a tiny patch.
void chamfered_cube(TriMesh& m, double cut) {
  std::vector<Point3> points;
  std::vector<std::array<int, 3>> faces;
  auto point = [&](const Point3& p) {
    for (size_t i = 0; i < points.size(); ++i)
      if (points[i] == p) return int(i);
    points.push_back(p);
    return int(points.size()) - 1;
  };
  auto fan = [&](std::vector<int> polygon) {  // convex, about the origin: orient outwards
    Point3 centre(0, 0, 0);
    for (int v : polygon) centre += points[v] / double(polygon.size());
    const Point3 n = (points[polygon[1]] - points[polygon[0]]) ^ (points[polygon[2]] - points[polygon[0]]);
    if (n * centre < 0) std::reverse(polygon.begin(), polygon.end());
    for (size_t k = 1; k + 1 < polygon.size(); ++k) faces.push_back({polygon[0], polygon[k], polygon[k + 1]});
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int sign : {-1, 1}) {
      // The face's corners in order around it; the cut corner gives its two cut points.
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      std::vector<int> polygon;
      for (auto [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        Point3 p;
        p[axis] = sign;
        p[u] = a;
        p[w] = b;
        if (p == Point3(1, 1, 1)) {
          Point3 before = p, after = p;  // along the sides to the previous and the next corner
          (b == 1 && a == 1 ? before[w] : after[u]) -= cut;
          (b == 1 && a == 1 ? after[u] : before[w]) -= cut;
          polygon.push_back(point(before));
          polygon.push_back(point(after));
        } else
          polygon.push_back(point(p));
      }
      fan(polygon);
    }
  fan({point(Point3(1 - cut, 1, 1)), point(Point3(1, 1 - cut, 1)), point(Point3(1, 1, 1 - cut))});
  test::build(m, points, faces);
}

// The cube [-1,1]^3 whose top is raised by `step` for x > 0: a step face across the top whose two
// lines end at tiny lines of length `step` on the front and the back.
void stepped_block(TriMesh& m, double step) {
  const double t = 1 + step;
  const std::vector<Point3> points = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},  // bottom B0-B3
                                      {-1, -1, 1},  {0, -1, 1},  {0, 1, 1},  {-1, 1, 1},   // top left TL0-TL3
                                      {0, -1, t},   {1, -1, t},  {1, 1, t},  {0, 1, t}};   // top right TR0-TR3
  std::vector<std::array<int, 3>> faces;
  auto quad = [&](int a, int b, int c, int d) {  // counter-clockwise seen from outside
    faces.push_back({a, b, c});
    faces.push_back({a, c, d});
  };
  quad(0, 3, 2, 1);    // bottom
  quad(4, 5, 6, 7);    // top left
  quad(8, 9, 10, 11);  // top right
  quad(5, 8, 11, 6);   // the step, facing -x
  quad(0, 4, 7, 3);    // x = -1
  quad(1, 2, 10, 9);   // x = +1
  // Front (y = -1) and back (y = +1): L-shaped, four triangles each.
  for (auto [a, b, c] : {std::array<int, 3>{0, 1, 5}, {1, 9, 5}, {9, 8, 5}, {0, 5, 4}}) {
    faces.push_back({a, b, c});
    auto back = [](int v) { return v + (v % 4 == 0 ? 3 : v % 4 == 1 ? 1 : v % 4 == 2 ? -1 : -3); };
    faces.push_back({back(a), back(c), back(b)});
  }
  test::build(m, points, faces);
}

remesh::Result remesh_at(const TriMesh& m, double size, TriMesh& out) {
  remesh::Params p;
  p.target_length = size;
  return remesh::remesh(m, p, out);
}

// Closed, two-manifold and of sphere topology: every edge on two faces, Euler characteristic 2.
void expect_closed_sphere(const TriMesh& out) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& f : out.face)
    for (int z = 0; z < 3; ++z)
      edges[std::minmax(int(vcg::tri::Index(out, f.cV(z))), int(vcg::tri::Index(out, f.cV((z + 1) % 3))))]++;
  for (const auto& [e, n] : edges) EXPECT_EQ(n, 2);
  EXPECT_EQ(int(out.vert.size()) - int(edges.size()) + int(out.face.size()), 2);
}

// A regrid with no side left open, closed as a sphere, whose worst angle is at least `degrees`.
void expect_whole_and_at_least(const remesh::Result& r, const TriMesh& out, double degrees) {
  EXPECT_EQ(r.unmeshed_sides, 0);
  expect_closed_sphere(out);
  EXPECT_GE(r.min_angle_deg, degrees);
}

int selected_vertices(const TriMesh& out) {  // the output's corners
  int n = 0;
  for (const auto& v : out.vert) n += v.IsS() ? 1 : 0;
  return n;
}

}  // namespace

TEST(RemeshCornerMerging, ATinyCutOffCornerBecomesOnePointAndItsPatchGoes) {
  // Cut 0.003 (lines of 0.0042) at a size of 0.2: one row of faces around the tiny triangle had
  // angles of about atan(0.0042 / 0.1) = 2.4 degrees.
  TriMesh m, out;
  chamfered_cube(m, 0.003);
  const remesh::Result r = remesh_at(m, 0.2, out);
  EXPECT_EQ(r.corners, 10);
  EXPECT_EQ(r.merged_corners, 2);
  EXPECT_EQ(selected_vertices(out), 8);  // the seven cube corners and the one point of the cut
  expect_whole_and_at_least(r, out, 30.0);  // 30.79 measured; 4.56 with every corner kept
  // The merged point is one of the cut's corners, within the cut of the cube's corner.
  double closest = 1e9;
  for (const auto& v : out.vert) closest = std::min(closest, (v.cP() - Point3(1, 1, 1)).Norm());
  EXPECT_NEAR(closest, 0.003, 1e-12);
}

TEST(RemeshCornerMerging, ACutAsLongAsAFifthOfTheSizeStays) {
  // Cut 0.2 (lines of 0.28) at a size of 0.2: a real facet, meshed with its three corners.
  TriMesh m, out;
  chamfered_cube(m, 0.2);
  const remesh::Result r = remesh_at(m, 0.2, out);
  EXPECT_EQ(r.merged_corners, 0);
  EXPECT_EQ(r.unmeshed_sides, 0);
  EXPECT_EQ(selected_vertices(out), 10);
}

TEST(RemeshCornerMerging, AStepLowerThanATenthOfTheSizeClosesWithItsTwoLinesSharingPoints) {
  // A step 0.002 high across the top at a size of 0.2: its ends are tiny lines, its two lines
  // become twins (the surfaces beyond both go the same way) and the step's strip is not meshed.
  TriMesh m, out;
  stepped_block(m, 0.002);
  const remesh::Result r = remesh_at(m, 0.2, out);
  EXPECT_EQ(r.merged_corners, 2);
  EXPECT_EQ(r.merged_lines, 1);
  expect_whole_and_at_least(r, out, 30.0);  // 35.19 measured; 2.10 with the step's strip meshed
}

TEST(RemeshCornerMerging, AThinPlatesRimStaysAStripOfOneLayer) {
  // A 100 x 50 x 0.1 plate at size 2: the rim's ends are tiny lines too, but the surfaces beyond
  // its two lines face apart; merged, the top and the bottom would meet in a knife edge.
  TriMesh m, out;
  test::cube(m, 1);
  for (auto& v : m.vert) v.P() = Point3(v.P()[0] * 50.0, v.P()[1] * 25.0, v.P()[2] * 0.05);
  const remesh::Result r = remesh_at(m, 2.0, out);
  EXPECT_EQ(r.merged_corners, 0);
  EXPECT_EQ(r.thin_patches, 4);
}
