#include "common/mesh_validation.h"

#include "common/errors.h"

#include <cmath>

namespace mr {

bool has_finite_coordinates(const TriMesh& mesh) {
  for (const auto& v : mesh.vert)
    if (!std::isfinite(v.cP()[0]) || !std::isfinite(v.cP()[1]) || !std::isfinite(v.cP()[2]))
      return false;
  return true;
}

void require_triangle_surface(const TriMesh& mesh, const std::string& what) {
  if (mesh.vert.empty())
    throw InvalidInput(what + " is empty: load a triangle mesh first");
  if (mesh.face.empty())
    throw InvalidInput(what + " has no faces (a point cloud?): this filter needs a triangle surface");
  if (mesh.vn != int(mesh.vert.size()) || mesh.fn != int(mesh.face.size()))
    throw InvalidInput(what + " is not compact (it has deleted elements): compact it first");
  if (!has_finite_coordinates(mesh))
    throw InvalidInput(what + " has NaN or infinite vertex coordinates: remove them first "
                       "(Cleaning and Repairing > Remove Unreferenced/Duplicate Vertices does not; "
                       "fix or delete those vertices)");
}

}  // namespace mr
