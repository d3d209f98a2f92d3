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
