// Synthetic shapes with known topology for the unit tests.
#pragma once

#include "common/tri_mesh.h"

namespace mr::test {

/// Builds a mesh from raw arrays (faces as vertex index triples).
void build(TriMesh& m, const std::vector<Point3>& points, const std::vector<std::array<int, 3>>& faces);

/// Axis-aligned cube [-1,1]^3, each square face split into 2*n*n triangles, outward oriented.
void cube(TriMesh& m, int n = 1);

/// Closed cylinder of the given radius and height: `segments` around, `rings` bands on the side,
/// caps fanned around a centre vertex.
void cylinder(TriMesh& m, int segments, int rings, double radius = 1.0, double height = 2.0);

/// Unit sphere, subdivided icosahedron.
void sphere(TriMesh& m, int subdivisions);

/// Flat n x n grid of squares on [0,1]^2 (open, one boundary loop).
void grid(TriMesh& m, int n);

}  // namespace mr::test
