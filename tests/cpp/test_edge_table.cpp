#include "common/edge_table.h"
#include "shapes.h"

#include <gtest/gtest.h>

using namespace mr;

TEST(EdgeTable, ClosedCubeHasEulerEdgeCountAndOnlyManifoldEdges) {
  TriMesh m;
  test::cube(m, 3);
  EdgeTable edges(m);
  // closed genus 0: E = V + F - 2
  EXPECT_EQ(edges.edge_count(), int(m.vert.size() + m.face.size()) - 2);
  for (int e = 0; e < edges.edge_count(); ++e) EXPECT_EQ(edges.valence(e), 2);
}

TEST(EdgeTable, GridHasBoundaryEdgesOnItsPerimeter) {
  TriMesh m;
  test::grid(m, 4);
  EdgeTable edges(m);
  int boundary = 0;
  for (int e = 0; e < edges.edge_count(); ++e) boundary += edges.valence(e) == 1;
  EXPECT_EQ(boundary, 16);
}

TEST(EdgeTable, ThreeFacesOnOneEdgeIsNonManifold) {
  TriMesh m;
  test::build(m, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}},
              {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  EdgeTable edges(m);
  int nm = 0;
  for (int e = 0; e < edges.edge_count(); ++e) nm += edges.valence(e) == 3;
  EXPECT_EQ(nm, 1);
  EXPECT_EQ(edges.opposite_face(0, 0), -1);
}

TEST(EdgeTable, OppositeFaceIsSymmetric) {
  TriMesh m;
  test::sphere(m, 2);
  EdgeTable edges(m);
  for (int f = 0; f < int(m.face.size()); ++f)
    for (int z = 0; z < 3; ++z) {
      int g = edges.opposite_face(f, z);
      ASSERT_GE(g, 0);
      bool back = false;
      for (int w = 0; w < 3; ++w) back |= edges.opposite_face(g, w) == f;
      EXPECT_TRUE(back);
    }
}

TEST(EdgeTable, IndexedTrianglesGiveTheMeshTableAndFindEveryEdge) {
  TriMesh m;
  test::sphere(m, 2);
  std::vector<std::array<int, 3>> tri;
  for (const auto& f : m.face)
    tri.push_back({int(vcg::tri::Index(m, f.cV(0))), int(vcg::tri::Index(m, f.cV(1))), int(vcg::tri::Index(m, f.cV(2)))});
  const EdgeTable a(m), b(m.vert.size(), tri);
  ASSERT_EQ(a.edge_count(), b.edge_count());
  for (int e = 0; e < a.edge_count(); ++e) {
    EXPECT_EQ(a.v0(e), b.v0(e));
    EXPECT_EQ(a.v1(e), b.v1(e));
    EXPECT_EQ(b.find(b.v1(e), b.v0(e)), e);  // either order
  }
  EXPECT_EQ(b.find(0, 0), -1);
  int missing = 0;  // a pair of vertices with no edge between them
  for (int v = 1; v < int(m.vert.size()) && missing == 0; ++v) missing = b.find(0, v) < 0 ? v : 0;
  ASSERT_GT(missing, 0);
}

TEST(EdgeTable, DegenerateSidesOfIndexedTrianglesGetNoEdge) {
  // A welded sliver (vertex 1 twice) beside a proper triangle.
  const EdgeTable edges(4, {{0, 1, 1}, {0, 2, 1}, {1, 2, 3}});
  EXPECT_EQ(edges.edge_of(0, 1), -1);  // side 1 -> 1
  EXPECT_GE(edges.edge_of(0, 0), 0);
  EXPECT_EQ(edges.valence(edges.find(0, 1)), 3);  // the sliver's two sides on 0-1 and the triangle's
  EXPECT_EQ(edges.edge_count(), 5);               // 0-1, 0-2, 1-2, 1-3, 2-3
}
