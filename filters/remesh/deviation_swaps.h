// Swaps that bring the output closer to the input surface: where a pair of faces bridges a
// crease stage 1 did not keep (a dropped short line, a rounded ridge below the ridge angle) the
// diagonal across the crease lies off the surface, while the other diagonal runs along it.
// The angle swaps of the post-pass only look at shapes and leave such pairs as they are.
#pragma once

#include "remesh/output_mesh.h"
#include "remesh/size_field.h"
#include "remesh/surface_locator.h"

#include <array>
#include <vector>

namespace mr::remesh {

struct DeviationSwapParams {
  /// Only face pairs farther than this x local size from the input are considered.
  double min_deviation = 0.1;
  /// A swap must bring the pair's distance below this fraction of what it was.
  double gain = 0.5;
  /// The new faces keep at least min(this, the old pair's smallest angle), degrees.
  double min_angle_deg = 30.0;
  /// The new diagonal stays within this x local size (or the old diagonal's length).
  double max_length = 1.4;
  int passes = 2;
};

/// Swaps non-feature edges of one patch whose face pair lies off the input when the other
/// diagonal follows it. Returns the number of swaps.
int swap_towards_surface(OutputMesh& out, const std::vector<std::array<int, 2>>& feature_edges,
                         const SurfaceLocator& locator, const SizeField& size,
                         const DeviationSwapParams& params = {});

}  // namespace mr::remesh
