// The unit square as an output mesh for the post-pass tests: kLatticeCells x kLatticeCells
// cells, each split by its rising diagonal (inner points have 6 neighbours), border points line
// points and the four corners corners, every point with its host face on the input grid.
#pragma once

#include "remesh/output_mesh.h"
#include "remesh/surface_locator.h"
#include "remesh/triangle_geometry.h"

#include <algorithm>

namespace mr::test {

constexpr int kLatticeCells = 10;  // cells per side: edges of 0.1

inline int lattice_id(int i, int j) { return j * (kLatticeCells + 1) + i; }

inline remesh::OutputMesh unit_lattice(const remesh::SurfaceLocator& locator) {
  using remesh::PointKind;
  const int n = kLatticeCells;
  remesh::OutputMesh out;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const Point3 p(double(i) / n, double(j) / n, 0);
      const bool border = i == 0 || j == 0 || i == n || j == n;
      const bool corner = (i == 0 || i == n) && (j == 0 || j == n);
      out.add_point(p, locator.locate(p, -1, Point3(0, 0, 1), -1, 0.2).face,
                    corner ? PointKind::Corner : border ? PointKind::Line : PointKind::Free);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      out.faces.push_back({lattice_id(i, j), lattice_id(i + 1, j), lattice_id(i + 1, j + 1)});
      out.faces.push_back({lattice_id(i, j), lattice_id(i + 1, j + 1), lattice_id(i, j + 1)});
    }
  out.face_patch.assign(out.faces.size(), 0);
  return out;
}

/// Smallest angle of any face, radians.
inline double worst_angle(const remesh::OutputMesh& out) {
  double w = 1e9;
  for (const auto& t : out.faces)
    w = std::min(w, remesh::min_angle(out.points[t[0]], out.points[t[1]], out.points[t[2]]));
  return w;
}

}  // namespace mr::test
