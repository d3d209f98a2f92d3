// A pair of faces on the same three points, facing apart, goes; everything else stays.
#include "remesh/flat_pockets.h"

#include <gtest/gtest.h>

using namespace mr;
using namespace mr::remesh;

namespace {

// A square of two faces (0 1 2, 0 2 3), and a triangle 1 4 2 on its side 1-2.
OutputMesh square_and_ear() {
  OutputMesh out;
  for (const Point3& p : {Point3(0, 0, 0), Point3(1, 0, 0), Point3(1, 1, 0), Point3(0, 1, 0), Point3(2, 0.5, 0)})
    out.add_point(p, 0, PointKind::Corner);
  out.faces = {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}};
  out.face_patch = {7, 7, 8};
  out.rebuild_shared_edges();
  return out;
}

}  // namespace

TEST(FlatPockets, AFacePairFacingApartGoesWithItsPatchesAndSharedEdges) {
  OutputMesh out = square_and_ear();
  out.faces.push_back({4, 1, 2});  // the ear again, facing the other way
  out.face_patch.push_back(8);
  out.rebuild_shared_edges();
  ASSERT_TRUE(out.shared_edges.count(OutputMesh::edge_key(1, 4)));
  EXPECT_EQ(remove_flat_pockets(out), 1);
  ASSERT_EQ(out.faces.size(), 2u);
  EXPECT_EQ(out.faces[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(out.faces[1], (std::array<int, 3>{0, 2, 3}));
  EXPECT_EQ(out.face_patch, (std::vector<int>{7, 7}));
  EXPECT_FALSE(out.shared_edges.count(OutputMesh::edge_key(1, 4)));  // only the square's edges left
  EXPECT_TRUE(out.shared_edges.count(OutputMesh::edge_key(0, 2)));
}

TEST(FlatPockets, FacesOnDifferentPointsOrFacingTheSameWayStay) {
  OutputMesh out = square_and_ear();
  EXPECT_EQ(remove_flat_pockets(out), 0);
  EXPECT_EQ(out.faces.size(), 3u);
  // A second copy facing the same way is not a pocket (and not the front's to make).
  out.faces.push_back({2, 1, 4});
  out.face_patch.push_back(8);
  EXPECT_EQ(remove_flat_pockets(out), 0);
  EXPECT_EQ(out.faces.size(), 4u);
}
