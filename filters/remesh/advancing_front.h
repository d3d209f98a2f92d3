// The advancing front on one patch of the discrete surface (Löhner 1996, section 3):
// the front side that forms the smallest new face goes first; a new point is placed
// for a well-shaped triangle and projected onto the patch, existing front points
// nearby are preferred, and every candidate is checked in 2D in the tangent plane
// of the host face against crossing nearby front sides.
#pragma once

#include "remesh/output_mesh.h"
#include "remesh/size_field.h"
#include "remesh/surface_locator.h"

#include <array>
#include <vector>

namespace mr::remesh {

struct FrontParams {
  /// Existing front points within this factor of the local size from the ideal point are tried
  /// before a new point.
  double prefer_existing = 0.7;
  /// A new point closer than this factor of the local size to a front point is not created.
  double min_point_distance = 0.55;
  /// A side that found no valid triangle is retried this many times (with relaxed checks) before
  /// it is left as an unmeshed front side.
  int max_retries = 4;
  /// The patch is narrower than the elements (a thin strip between two lines): its boundary
  /// loops are triangulated directly by ear clipping, one layer of faces, no new points.
  bool thin_patch = false;
  /// Faces of the output already there around a hole being meshed again: new faces may neither
  /// cover them nor repeat their edges.
  std::vector<int> meshed_faces;
  /// Work left for the whole run (every front, repairs and retries included), counted like each
  /// front's own bound; a front stops when it is spent. Null: no run-wide bound.
  long* checks_left = nullptr;
};

/// Directed front side a->b: the unmeshed part of the patch lies to its left (seen from the
/// surface normal), i.e. the side is oriented like the input faces bounding that part.
using FrontSide = std::array<int, 2>;

struct FrontResult {
  int faces = 0;
  int new_points = 0;
  int unmeshed_sides = 0;   ///< front sides left when the front could not close
  std::vector<FrontSide> open_sides;  ///< those sides, sorted
  long iterations = 0;
  bool iteration_limit = false;
};

/// Fills patch `patch` of the locator's surface starting from `front`; appends points and faces
/// to `out`. A patch with an empty front gets a seed triangle. Never loops forever: the number
/// of steps is bounded and a side that cannot be closed is reported in unmeshed_sides.
FrontResult advance_front(OutputMesh& out, std::vector<FrontSide> front, int patch, const SurfaceLocator& locator,
                          const SizeField& size, const FrontParams& params = {});

/// Priority of a front side: sides forming smaller faces first (shorter, and fewer failures).
double front_priority(double side_length, int failures);

}  // namespace mr::remesh
