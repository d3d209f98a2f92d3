#include "common/mesh_validation.h"

#include "common/errors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

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

int count_duplicate_faces(const TriMesh& mesh) {
  std::vector<std::array<int, 3>> keys;
  keys.reserve(mesh.face.size());
  for (const auto& f : mesh.face) {
    std::array<int, 3> k;
    for (int z = 0; z < 3; ++z) k[z] = int(vcg::tri::Index(mesh, f.cV(z)));
    std::sort(k.begin(), k.end());
    keys.push_back(k);
  }
  std::sort(keys.begin(), keys.end());
  int duplicates = 0;
  for (size_t i = 1; i < keys.size(); ++i) duplicates += keys[i] == keys[i - 1];
  return duplicates;
}

void require_no_duplicate_faces(const TriMesh& mesh, const std::string& what) {
  if (const int n = count_duplicate_faces(mesh))
    throw InvalidInput(what + " has " + std::to_string(n) +
                       " duplicate faces (the same three vertices as another face, a double layer whose "
                       "edges are all non-manifold): remove them first (Cleaning and Repairing > Remove "
                       "Duplicate Faces)");
}

void require_some_area(const TriMesh& mesh, const std::string& what) {
  for (const auto& f : mesh.face)
    if (vcg::DoubleArea(f) > 0) return;
  throw InvalidInput(what + " has no face of nonzero area (every face is degenerate: a repeated or "
                     "collinear corner): there is no surface to work on (Cleaning and Repairing > Remove "
                     "Zero Area Faces removes them)");
}

}  // namespace mr
