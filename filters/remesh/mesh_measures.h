// Quality measurements of the output reported by the filter.
#pragma once

#include "remesh/output_mesh.h"
#include "remesh/size_field.h"
#include "remesh/surface_locator.h"
#include "remesh/wedge_tips.h"

namespace mr::remesh {

/// Edges within [kShortEdge, kLongEdge] x the local size are in range (issue #3's measure).
constexpr double kShortEdge = 0.7;
constexpr double kLongEdge = 1.4;

struct Measures {
  double min_angle_deg = 0, mean_min_angle_deg = 0, edges_in_range = 0, hausdorff = 0;
};

/// Angles, the share of edges in range, and a two-sided Hausdorff
/// estimate between `out` and the input surface of `input_locator`.
Measures measure(const OutputMesh& out, const SurfaceLocator& input_locator, const SizeField& size);

/// The size field at point v's place on its host face (the largest size when it has none).
double size_at_point(const OutputMesh& out, const SurfaceLocator& locator, const SizeField& size, int v);

/// Points of `out` whose faces make more than one fan (the surface is not manifold there).
int count_pinched_points(const OutputMesh& out);

/// Angles the feature lines themselves bound: where two feature edges leave a point at an
/// angle under kWedgeBoundDeg and one face fills the wedge between them, no mesh that keeps the
/// lines can give that corner more than the wedge's own angle (wedge_tips.h).
struct WedgeMeasure {
  int wedge_tips = 0;                 ///< such face corners
  double min_wedge_angle_deg = 180;   ///< the narrowest of them
  double min_angle_off_wedges_deg = 180;  ///< the smallest face angle at every other corner
};

/// The corners of `out`'s faces split into wedge tips between `feature_edges` and the rest.
WedgeMeasure measure_wedges(const OutputMesh& out, const std::vector<std::array<int, 2>>& feature_edges);

/// How many of `edges` (feature line segments) are no edge of any face of `out`.
int count_missing_edges(const OutputMesh& out, const std::vector<std::array<int, 2>>& edges);

}  // namespace mr::remesh
