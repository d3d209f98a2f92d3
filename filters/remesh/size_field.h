// The element size field: a target length at every input vertex, linearly
// interpolated over the input faces (Löhner 1996, section 3.1).
#pragma once

#include "remesh/surface_locator.h"

#include <array>
#include <vector>

namespace mr::remesh {

struct SizeParams {
  double target_length = 0;      ///< uniform size (> 0)
  /// Chord-error bound: where the surface bends, h <= sqrt(8 * error * R) (0 = off).
  double max_surface_error = 0;
  /// Sizes grow by at most this factor per element length: |h(u)-h(v)| <= (g-1)|uv| (>= 1).
  double gradation = 1.3;
  /// Point sources: positions and sizes, limiting h around them (after gradation).
  std::vector<Point3> source_points;
  std::vector<double> source_sizes;
  /// Line sources: segments between two source points, the size interpolated along them.
  std::vector<std::array<int, 2>> source_segments;
  /// Optional per-vertex upper bounds (e.g. small features).
  std::vector<double> vertex_cap;
  /// The caps spread with this gradation when it is larger than `gradation` (then they refine
  /// only close around a small feature), else with `gradation`, like the rest of the field.
  double cap_gradation = 1.0;
};

class SizeField {
public:
  /// Sizes at the surface's vertices. Curvature is measured across edges inside one group only,
  /// so ridges between patches do not shrink the size.
  SizeField(const Surface& surface, const SizeParams& params);
  /// Builds a field with given per-vertex sizes (tests).
  SizeField(const Surface& surface, std::vector<double> vertex_size);

  /// The same field with every size times `factor`.
  SizeField scaled(double factor) const;

  /// Size at barycentric coordinates `bary` of face f.
  double at(int face, const std::array<double, 3>& bary) const;
  double at_vertex(int v) const { return vertex_size_[v]; }
  double min_size() const { return min_; }
  double max_size() const { return max_; }

private:
  void limit_gradation(double gradation);
  void update_range();

  const Surface& surface_;
  std::vector<double> vertex_size_;
  double min_ = 0, max_ = 0;
};

}  // namespace mr::remesh
