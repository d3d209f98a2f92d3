// Quad meshes for the interpolatory subdivision: plain arrays, converted from and to
// MeshLab's representation (triangle pairs whose shared diagonal is a faux edge).
#pragma once

#include "common/tri_mesh.h"

#include <array>
#include <utility>
#include <vector>

namespace mr::quadsub {

struct QuadMesh {
  std::vector<Point3> points;
  std::vector<std::array<int, 4>> quads;  ///< counter-clockwise corner indices
};

/// Polygons of a triangle mesh: faces joined through faux edges (IsF) form one polygon.
/// `polygon_of_face`, when given, receives the polygon of each triangle.
/// \throw InvalidInput when a faux-edge region is not a simple polygon.
std::vector<std::vector<int>> polygons_from_faux_edges(const TriMesh& mesh, std::vector<int>* polygon_of_face = nullptr);

/// Quads of a polygon mesh, conforming: every non-quad is split into quads around its
/// centroid through its edge midpoints; so that no midpoint hangs, each quad strip leading
/// away from a split side is split in two through the midpoints of its opposite sides (a quad
/// crossed by two strips into four). Pure quad meshes come back unchanged. The input points
/// keep their indices. `polygon_of_quad`, when given, receives the polygon of each quad.
QuadMesh quads_from_polygons(const std::vector<Point3>& points, const std::vector<std::vector<int>>& polygons,
                             std::vector<int>* polygon_of_quad = nullptr);

/// Triangle pairs with faux diagonals, the way MeshLab stores quads.
void quads_to_tri_mesh(const QuadMesh& quads, TriMesh& out);

/// The same, followed by plain triangles (faces 2 * quads.quads.size() + t), which use
/// the points of `quads`.
void quads_to_tri_mesh(const QuadMesh& quads, const std::vector<std::array<int, 3>>& triangles, TriMesh& out);

}  // namespace mr::quadsub
