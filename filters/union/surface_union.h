// Boolean union of many closed triangulated bodies computed directly on their
// triangulations (Shostko, Löhner, Sandberg 1999): candidate face pairs from a grid,
// exact triangle-triangle intersection, re-triangulation of cut faces with the
// intersection segments as constraints, outside surface by a flood fill from an
// extreme face, sliver removal by edge collapse.
#pragma once

#include "common/tri_mesh.h"

#include <array>
#include <string>
#include <vector>

namespace mr::surface_union {

/// One closed body: positions, outward-oriented triangles and a name for messages.
struct Body {
  std::string name;
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> faces;
};

struct Params {
  /// Collapse edges of faces with a smaller minimum angle (degrees) after the cut,
  /// when that improves quality, flips no normal and keeps the intersection lines.
  /// 0 turns the step off.
  double sliver_angle_deg = 10.0;
  /// Bound on how far (relative to the bounding-box diagonal) the sliver step may move
  /// the surface from where the cut left it, all its moves together (checked at samples of
  /// every face it makes); moves that would change the shape more are skipped.
  double sliver_max_deviation = 2e-3;
  /// Bound on the total volume change of all sliver moves, relative to the volume.
  double sliver_max_volume_change = 1e-6;
  /// Refuse bodies that cross themselves (self_intersection.h). Off: such a body gives an
  /// undefined result, at less cost for inputs known to be clean.
  bool check_self_intersections = true;
};

/// The angle under which Result::slivers_left counts faces: the quality bar
/// (MeshLab's union, CGAL and manifold3d leave 2 to 27% of their faces under it).
constexpr double kReportedSliverDeg = 5.0;

struct Result {
  std::vector<std::array<double, 3>> vertices;
  std::vector<std::array<int, 3>> faces;          ///< outward oriented
  std::vector<std::array<bool, 3>> line_edge;     ///< side z of face f lies on an intersection line
  /// Per face: the input face it lies in (or, after the sliver step, the one its slot came
  /// from: within the deviation bound of it), as an index into all bodies' faces in order,
  /// body 0's first (source_attributes.h maps it back).
  std::vector<int> face_source;
  std::vector<std::vector<int>> lines;            ///< intersection polylines (vertex indices)
  std::vector<bool> line_closed;
  int bodies = 0;
  int bodies_reoriented = 0;                      ///< inward-oriented bodies that were flipped
  int candidate_pairs = 0;                        ///< face pairs with overlapping boxes
  int intersecting_face_pairs = 0;
  int intersecting_pairs = 0;                     ///< pairs of bodies that intersect
  int intersection_points = 0;                    ///< distinct constructed points
  int intersection_edges = 0;
  int cut_faces = 0;
  int faces_removed = 0;                          ///< sub-faces inside the union (or duplicated)
  int slivers_collapsed = 0;
  int flat_flips = 0;                             ///< edges between the input's own flat slivers the sliver step flipped (moving nothing)
  int sliver_parts = 0;                           ///< parts of the surface the sliver step treated at once (1 or 2; 0: no step)
  int orientation_conflicts = 0;                  ///< fill steps into a same-oriented face (should be 0)
  int doubled_edges_split = 0;                    ///< edges of two touching sheets split apart (doubled_edges.h)
  int rounded_caps_split = 0;                     ///< faces rounding flattened onto a side, removed (rounded_caps.h)
  int rounded_edges_merged = 0;                   ///< vertices merged away where rounding left edges without length or next to none (rounded_edges.h)
  double min_angle_deg = 0;                       ///< smallest angle in the output
  int slivers_left = 0;                           ///< output faces under kReportedSliverDeg worse than the input face they lie in (slivers_left.h)
  std::vector<int> slivers_left_faces;            ///< those faces (indices into faces, ascending)
  double time_pairs_ms = 0, time_intersect_ms = 0, time_retriangulate_ms = 0, time_classify_ms = 0,
         time_slivers_ms = 0, time_total_ms = 0;
};

/// \throw InvalidInput when there is no body, a body is empty, has non-finite
///        coordinates or a degenerate (zero-area) face; TopologyError when a body is
///        open, non-manifold or inconsistently oriented. Messages name the body.
Result compute_union(const std::vector<Body>& bodies, const Params& params = {});

/// A body from a whole mesh.
Body body_from_mesh(const TriMesh& mesh, const std::string& name);

/// One body per face-connected component of `mesh` (named "component k"); `mesh_faces`
/// (if given) gets, per body, the index in `mesh.face` of each of its faces.
std::vector<Body> bodies_from_components(const TriMesh& mesh, std::vector<std::vector<int>>* mesh_faces = nullptr);

/// Writes the union into `out` (cleared): faces, and the intersection edges as the
/// per-face-edge selection (FaceEdgeS).
void to_tri_mesh(const Result& r, TriMesh& out);

}  // namespace mr::surface_union
