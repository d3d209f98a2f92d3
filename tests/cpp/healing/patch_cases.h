// Patch sets with known defects for the healing tests: the six faces of a
// cube, each triangulated on its own.
#pragma once

#include "common/tri_mesh.h"

#include <array>
#include <vector>

namespace mr::test {

struct BoxPatches {
  std::vector<int> resolution = {2, 3, 4, 2, 3, 5};  ///< grid squares per side, per cube face
  double offset = 0;        ///< each face moves this far along its outward normal (opens gaps)
  double overlap = 0;       ///< each face grows this far past the cube edges (overlaps)
  std::vector<bool> flip;   ///< faces with reversed orientation
};

/// Cube [-1,1]^3 as six separate patches (no shared vertices); face k's
/// triangles carry patch k in `face_patch`.
void box_patches(TriMesh& m, std::vector<int>& face_patch, const BoxPatches& spec);

/// Signed volume of a closed, consistently oriented mesh.
double signed_volume(const TriMesh& m);

/// Number of edges with one face, and with more than two faces.
int boundary_edge_count(const TriMesh& m);
int non_manifold_edge_count(const TriMesh& m);

/// True if every edge with two faces is used in opposite directions.
bool consistently_oriented(const TriMesh& m);

}  // namespace mr::test
