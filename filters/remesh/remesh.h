// Advancing-front regridding of a triangulated surface, after
// R. Löhner, "Regridding Surface Triangulations", J. Comput. Phys. 126 (1996).
// Feature lines from stage 1 are re-discretised first (corners kept exactly, line
// points on the input polylines); each patch is then filled by an advancing front
// on the discrete surface, so no face crosses a ridge.
#pragma once

#include "common/tri_mesh.h"

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace mr::remesh {

/// Post-generation surface recovery (section 4 of the paper).
enum class Recovery {
  Linear = 0,         ///< points stay on the input triangles
  ClosestVertex = 1,  ///< free points move to the closest input vertex of their host face
  Quadratic = 2,      ///< quadratic triangles with Hermite mid-side points from vertex normals
  Cubic = 3           ///< cubic triangles from vertex positions and normals
};

struct Params {
  double target_length = 0;        ///< absolute element size (> 0, below the bbox diagonal)
  double ridge_angle_deg = 30.0;   ///< stage 1 ridge angle
  double corner_angle_deg = 45.0;  ///< stage 1 corner angle
  /// Stage 1 feature-noise suppression (features::Params::min_line_length), absolute;
  /// negative = the target length, 0 keeps every ridge (strict mode).
  double min_line_length = -1;
  double max_surface_error = 0;    ///< chord-error bound for curvature adaptation (0 = uniform)
  double gradation = 1.3;          ///< size growth limit per element (>= 1)
  Recovery recovery = Recovery::Linear;
  int improvement_iterations = 3;  ///< swap and smoothing sweeps (0 = off)
  bool use_selected_edges_as_ridges = false;  ///< also keep the input's face-edge selection (FaceEdgeS) as ridges
  /// Lines meeting at a wedge under 30 degrees may share their first segment (wedge_relaxing.h).
  bool relax_wedges = false;
  std::vector<Point3> source_points;  ///< point sources of size
  std::vector<double> source_sizes;
  std::vector<std::array<int, 2>> source_segments;  ///< line sources: pairs of source points
  /// Progress in percent with a message; may be empty.
  std::function<void(int, const char*)> progress;
};

struct Result {
  int corners = 0, lines = 0, patches = 0;
  int suppressed_lines = 0;     ///< short dangling lines and loops stage 1 dropped
  int suppressed_folded_slivers = 0;  ///< of those, sliver patches bordered by a fold
  int suppressed_crumples = 0;  ///< of those, crumples (patches turned over against the surface around)
  int feature_edges = 0;
  int merged_lines = 0;         ///< lines merged with a nearly coincident twin (sliver patch dropped)
  int merged_corners = 0;       ///< corners that share the point of a corner a tiny line joins them to (corner_merging.h)
  int thin_patches = 0;         ///< strips narrower than the elements, given one layer of faces
  int thin_step_faces = 0;      ///< input faces of thin steps whose corners capped the size (thin_step_caps.h)
  int narrow_rim_faces = 0;     ///< input faces across narrow rims and slots whose corners capped the size (thin_step_caps.h)
  int neck_points = 0;          ///< line points at necks between lines that capped the size (neck_caps.h)
  int unmeshed_sides = 0;       ///< front sides that could not be closed (0 = complete)
  int unmeshed_patches = 0;     ///< patches with unmeshed sides
  /// Patches whose front stopped at its step or work bound, closed by the last resort or left
  /// open (those are in unmeshed_patches too).
  int bounded_patches = 0;
  /// Feature line segments that are no edge of the output: no hole, the faces closed over
  /// them (the end of a dangling line a hair beside another line or corner).
  int missing_feature_edges = 0;
  int flat_pockets_removed = 0;  ///< face pairs on the same three points, facing apart (flat_pockets.h)
  /// The first regridding left sides open or points not manifold, and a later one that kept
  /// the sliver patches bordered by folds (stage 1's keep_folded_slivers) left fewer: this is it.
  bool kept_folded_slivers = false;
  /// The first regridding left sides open or points not manifold, and a second one that kept
  /// the crumples stage 1 had dropped as patches did better: this is the second (or the third,
  /// with kept_folded_slivers).
  bool kept_crumples = false;
  int non_manifold_points = 0;  ///< output points whose faces make more than one fan
  int retried_patches = 0;      ///< patch meshings repeated with smaller elements
  int local_repairs = 0;        ///< holes around open sides or pinched points meshed again, smaller
  int remeshed_off_lines = 0;   ///< patches meshed again without an edge along a line of other patches
  int swaps = 0, smoothed = 0;  ///< post-pass moves
  int collapsed = 0;            ///< post-pass: free points removed at short edges
  int split = 0;                ///< post-pass: long edges split at their middle
  int line_points_removed = 0;  ///< post-pass: line points whose two segments became one
  int relaxed_wedges = 0;       ///< post-pass: wedge tips whose two lines now share their first segment
  int closed_line_gaps = 0;     ///< post-pass: points where two lines that passed close now meet
  int jointly_moved = 0;        ///< post-pass: points moved together around faces under 30 degrees
  int snapped = 0;              ///< free points moved onto input vertices the output cut off
  int surface_swaps = 0;        ///< edges swapped to follow the input across creases not kept
  double min_angle_deg = 0;     ///< worst triangle angle
  /// Face corners between two feature edges under kWedgeBoundDeg (wedge_tips.h), one face
  /// filling the wedge: the lines bound those angles, no regridding that keeps them can do better.
  int wedge_tips = 0;
  double min_wedge_angle_deg = 180;       ///< the narrowest wedge tip
  double min_angle_off_wedges_deg = 0;    ///< worst angle at every other face corner
  double mean_min_angle_deg = 0;  ///< mean over triangles of their smallest angle
  double edges_in_range = 0;    ///< share of edges with length in [0.7,1.4] x local size
  double hausdorff = 0;         ///< two-sided estimate (vertices, edge midpoints, centroids), absolute
  double diagonal = 0;          ///< input bbox diagonal
};

/// Remeshes `input` (not modified) into `output` (cleared first): feature edges are flagged
/// with FaceEdgeS, corners are selected vertices, and vertex quality holds the point kind
/// (0 free, 1 on a feature line, 2 corner).
/// \pre input is compact.
/// \throw InvalidInput on empty input, a point cloud, NaN coordinates, a target length <= 0 or
///        larger than the bbox diagonal, or other bad parameters.
Result remesh(const TriMesh& input, const Params& params, TriMesh& output);

}  // namespace mr::remesh
