// The unit square as a patch to mesh in the remesher's tests: the input grid, its locator and a
// uniform size field, and the square's boundary as a front.
#pragma once

#include "remesh/advancing_front.h"
#include "remesh/size_field.h"
#include "remesh/surface_locator.h"
#include "shapes.h"

#include <vector>

namespace mr::test {

struct UnitGrid {
  TriMesh mesh;
  UnitGrid() { grid(mesh, 4); }
};

struct UnitSquare : UnitGrid {
  remesh::Surface surface;
  remesh::SurfaceLocator locator;
  remesh::SizeField size;

  explicit UnitSquare(double h)
      : surface(remesh::Surface::from_mesh(mesh, {})), locator(surface, 0.1),
        size(surface, std::vector<double>(surface.points.size(), h)) {}

  /// The boundary's line points, 10 per side, counter-clockwise from the origin, added to `out`;
  /// as a front counter-clockwise (the square to its left) or clockwise (outside to its left).
  static std::vector<remesh::FrontSide> boundary(remesh::OutputMesh& out, bool counter_clockwise = true) {
    std::vector<int> ring;
    for (int k = 0; k < 40; ++k) {
      const int side = k / 10;
      const double t = (k % 10) / 10.0;
      const Point3 p = side == 0 ? Point3(t, 0, 0) : side == 1 ? Point3(1, t, 0) : side == 2 ? Point3(1 - t, 1, 0) : Point3(0, 1 - t, 0);
      ring.push_back(out.add_point(p, -1, remesh::PointKind::Line));
    }
    std::vector<remesh::FrontSide> front;
    for (int k = 0; k < 40; ++k)
      front.push_back(counter_clockwise ? remesh::FrontSide{ring[k], ring[(k + 1) % 40]}
                                        : remesh::FrontSide{ring[(k + 1) % 40], ring[k]});
    return front;
  }
};

}  // namespace mr::test
