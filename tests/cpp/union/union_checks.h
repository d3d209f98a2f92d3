// Measurements the union tests assert on.
#pragma once

#include "union/surface_union.h"

namespace mr::test {

struct Watertight {
  int boundary_edges = 0, nonmanifold_edges = 0, misoriented_edges = 0;
  bool ok() const { return boundary_edges == 0 && nonmanifold_edges == 0 && misoriented_edges == 0; }
};

Watertight watertight(const surface_union::Result& r);
double volume(const surface_union::Result& r);
double volume(const surface_union::Body& b);
surface_union::Body make_body(const TriMesh& m, double dx = 0, double dy = 0, double dz = 0, double scale = 1);

}  // namespace mr::test
