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
