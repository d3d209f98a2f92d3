// The mesh the remesher builds: flat arrays with, per vertex, its host face on the
// input surface and whether it is a corner, a point of a feature line or free.
#pragma once

#include "common/tri_mesh.h"

#include <array>
#include <vector>

namespace mr::remesh {

enum class PointKind : char { Free = 0, Line = 1, Corner = 2 };

struct OutputMesh {
  std::vector<Point3> points;
  std::vector<int> host;         ///< host face on the input surface
  std::vector<PointKind> kind;
  std::vector<std::array<int, 3>> faces;
  std::vector<int> face_patch;   ///< input patch each face was generated in

  int add_point(const Point3& p, int host_face, PointKind k) {
    points.push_back(p);
    host.push_back(host_face);
    kind.push_back(k);
    return int(points.size()) - 1;
  }
};

}  // namespace mr::remesh
