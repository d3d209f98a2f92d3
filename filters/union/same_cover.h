// Whether a local change of the surface leaves it covering exactly the same points.
// Such a change cannot make faces meet that did not, so the sliver step may skip its
// crossing check: on CAD plates that check meets many coplanar neighbours and is the
// most expensive part of a move.
#pragma once

#include "union/face_clearance.h"

#include <array>
#include <vector>

namespace mr::surface_union {

/// A face by its corners' ids and positions.
struct PlacedFace {
  std::array<int, 3> id;
  std::array<V3, 3> at;
};

/// The coordinate axis across whose plane triangle t lies (CAD plates), or -1: a test of
/// equal doubles.
int axis_plane(const V3 t[3]);

/// The faces `after` cover exactly the points the faces `before` cover. Decided
/// exactly, and only in the simple cases: the faces fall into a few planes across
/// coordinate axes (CAD), or all lie in one plane, and in each plane all of them turn the same way and the boundary of the old faces
/// equals the boundary of the new ones, but for corners on a straight run of it (a
/// vertex moved or removed along a line). Then, plane by plane, the new triangles
/// cover each point as often as the old ones (the winding number of the common
/// boundary). Corners are told apart by id; a corner with the same id at another
/// position has moved. Returns false whenever it cannot tell.
bool same_cover(const std::vector<PlacedFace>& before, const std::vector<PlacedFace>& after);

}  // namespace mr::surface_union
