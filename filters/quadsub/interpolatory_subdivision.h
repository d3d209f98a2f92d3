// Interpolatory subdivision of quadrilateral nets of arbitrary topology, after
// L. Kobbelt, T. Hesse, H. Prautzsch, K. Schweizerhof, "Iterative Mesh Generation for
// FE-Computations on Free Form Surfaces", Engineering Computations 14 (1997), and
// L. Kobbelt, "Interpolatory Subdivision on Open Quadrilateral Nets with Arbitrary
// Topology", Computer Graphics Forum 15(3) (1996).
#pragma once

#include "quadsub/quad_mesh.h"

#include <utility>
#include <vector>

namespace mr::quadsub {

using EdgeList = std::vector<std::pair<int, int>>;

struct Params {
  int iterations = 1;               ///< subdivision steps, >= 1
  double w = 1.0;                   ///< tension, [0, sqrt(5)-1]: 1 = cubic precision, 0 = midpoints
  double corner_angle_deg = 60.0;   ///< a boundary or crease turning by more than this is a corner
  double crease_angle_deg = 0.0;    ///< edges whose faces meet at more than this are creases (0 = off)
  /// Input vertices where the surface comes to a point (the tip of a cone): every edge
  /// curve through a cusp ends there along its own edge (the point beyond the cusp is the
  /// reflection 2c - b of the neighbour), as if a hole had shrunk to the point, so there is
  /// no tangent plane. Indices stay valid at every level (old vertices keep their index).
  std::vector<int> cusp_vertices;
};

struct Result {
  QuadMesh mesh;
  EdgeList creases;                 ///< crease edges of the result (both halves of each input crease)
  int vertices_in = 0, faces_in = 0;
  int extraordinary_vertices = 0;   ///< interior vertices of valence != 4 in the input quad mesh
  int crease_edges_in = 0;
  int cusps = 0;
  int levels = 0;
};

/// Weight of the diagonal correction in the virtual point at an extraordinary vertex:
/// q* = 4/n sum(p_i) - (p_{j-1} + p_j + p_{j+1}) + gamma (4/n sum(d_i) - (d_{j-2} + d_{j-1} + d_j + d_{j+1})).
/// Equal face points from both directions next to the vertex require gamma = -w / (8 + w).
double diagonal_correction_weight(double w);

/// One subdivision step; `face_points_by_direction`, when given, receives for every
/// face the face point computed across each pair of opposite edges.
/// The result keeps `mesh.points` as the prefix of its points; quad q of `mesh` becomes
/// quads 4q+k (k = 0..3) = {c[k], edge point of (c[k], c[k+1]), face point, edge point of
/// (c[k-1], c[k])}, c = mesh.quads[q]; an edge point is one vertex shared by both faces of its edge.
QuadMesh subdivide_step(const QuadMesh& mesh, const EdgeList& creases, const Params& params, EdgeList* new_creases,
                        std::vector<std::pair<Point3, Point3>>* face_points_by_direction = nullptr);

/// Level 0 of `subdivide`: validates, splits non-quads into quads and finds the creases
/// (marked edges plus the crease angle); `levels` is 0 and `mesh` the quads to refine.
/// `polygon_of_quad`, when given, receives the input polygon of each quad.
/// \throw as `subdivide`.
Result prepare_level_zero(const std::vector<Point3>& points, const std::vector<std::vector<int>>& polygons,
                          const EdgeList& marked_creases, const Params& params,
                          std::vector<int>* polygon_of_quad = nullptr);

/// Splits non-quads, finds creases (marked edges plus the crease angle), runs the steps.
/// \throw InvalidInput on bad parameters, empty input or NaN; TopologyError on
///        non-manifold or inconsistently oriented input.
Result subdivide(const std::vector<Point3>& points, const std::vector<std::vector<int>>& polygons,
                 const EdgeList& marked_creases, const Params& params);

}  // namespace mr::quadsub
