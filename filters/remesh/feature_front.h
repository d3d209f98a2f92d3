// Feature lines re-discretised with the size field (points on the input polyline,
// corners kept exactly) and the initial front of every patch built from them
// (Löhner 1996, section 3: the lines are meshed first and bound the patches).
#pragma once

#include "features/feature_lines.h"
#include "remesh/advancing_front.h"
#include "remesh/line_sliding.h"
#include "remesh/output_mesh.h"
#include "remesh/size_field.h"

#include <array>
#include <vector>

namespace mr::remesh {

/// Lines closer than this times the size are twins around a sliver patch; a strip lower than it
/// is thin (one layer of faces).
constexpr double kSliverGap = 0.1;

struct FeatureFront {
  std::vector<std::vector<FrontSide>> patch_front;  ///< per patch, oriented like its input faces
  std::vector<std::array<int, 2>> feature_edges;    ///< output edges along the lines
  std::vector<int> corner_point;                    ///< output point of each input corner (same order)
  /// Sliver patches between two nearly coincident lines: not meshed (their lines share points).
  std::vector<char> dropped_patch;
  /// Patches whose faces all span between line points and are lower than kSliverGap x size:
  /// a thin strip (the rim of a thin plate) that takes one layer of faces between its lines.
  std::vector<char> thin_patch;
  int merged_lines = 0;  ///< lines that took the points of a nearly coincident twin
  int merged_corners = 0;  ///< corners that took the point of a corner joined to them by a tiny line
  /// Every line with its input polyline, for sliding its points later (twins once).
  std::vector<LinePath> line_paths;
};

/// Largest distance from a vertex of one polyline to the other polyline (both ways).
double polyline_gap(const std::vector<Point3>& a, const std::vector<Point3>& b);

/// Lines through surface vertices `a` and `b` lie within kSliverGap x the smallest size on
/// either of each other (twins: no element of that size fits between them).
bool within_sliver_gap(const Surface& s, const SizeField& size, const std::vector<int>& a, const std::vector<int>& b);

/// Number of segments for a polyline of `lengths` whose vertices have sizes `sizes`
/// (one more than lengths): the size-weighted length rounded, at least `min_segments`.
int segment_count(const std::vector<double>& lengths, const std::vector<double>& sizes, int min_segments);

/// Appends corner and line points to `out` and returns the patch fronts. Two open lines between
/// the same corners closer than a tenth of the local size, around a patch whose faces all lie on
/// them (a sliver, as in noisy scans), get the same points and that patch is dropped. With
/// `merge_tiny_lines`, corners joined by a tiny line share one point (corner_merging.h).
FeatureFront discretise_features(const TriMesh& mesh, const features::Result& features, const Surface& surface,
                                 const SizeField& size, OutputMesh& out, bool merge_tiny_lines = true);

}  // namespace mr::remesh
