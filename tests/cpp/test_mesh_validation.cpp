#include "common/errors.h"
#include "common/mesh_validation.h"
#include "shapes.h"

#include <gtest/gtest.h>

#include <limits>

using namespace mr;

TEST(MeshValidation, EmptyMeshIsRejected) {
  TriMesh m;
  EXPECT_THROW(require_triangle_surface(m), InvalidInput);
}

TEST(MeshValidation, PointCloudIsRejected) {
  TriMesh m;
  vcg::tri::Allocator<TriMesh>::AddVertices(m, 3);
  EXPECT_THROW(require_triangle_surface(m), InvalidInput);
}

TEST(MeshValidation, NaNCoordinateIsRejectedWithMessage) {
  TriMesh m;
  test::cube(m, 1);
  m.vert[2].P()[1] = std::numeric_limits<double>::quiet_NaN();
  try {
    require_triangle_surface(m, "body 2");
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("body 2"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("NaN"), std::string::npos);
  }
}

TEST(MeshValidation, CleanCubePasses) {
  TriMesh m;
  test::cube(m, 2);
  EXPECT_NO_THROW(require_triangle_surface(m));
}

TEST(MeshValidation, DuplicateFacesAreCountedInAnyOrderAndRejected) {
  TriMesh m;
  test::cube(m, 1);
  EXPECT_EQ(count_duplicate_faces(m), 0);
  EXPECT_NO_THROW(require_no_duplicate_faces(m));
  // Face 0 again, reversed (the other side of a zero-thickness double layer), and face 3
  // again with its corners rotated.
  auto v = [&](int f, int z) { return m.face[f].V(z); };
  auto f = vcg::tri::Allocator<TriMesh>::AddFaces(m, 2);
  f->V(0) = v(0, 0), f->V(1) = v(0, 2), f->V(2) = v(0, 1);
  ++f;
  f->V(0) = v(3, 1), f->V(1) = v(3, 2), f->V(2) = v(3, 0);
  EXPECT_EQ(count_duplicate_faces(m), 2);
  try {
    require_no_duplicate_faces(m);
    FAIL() << "no exception";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("2 duplicate faces"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("Remove Duplicate Faces"), std::string::npos);
  }
}
