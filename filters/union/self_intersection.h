// A body that crosses itself has no inside that the union could be decided by. Found
// before any work: bodies star-shaped about their vertex centroid (convex ones, blobs)
// cannot cross themselves; on the others the face pairs whose boxes overlap
// (face_clearance's grid) get the exact triangle test of face_clearance.h, but where the
// surface is locally convex.
#pragma once

#include "common/edge_table.h"
#include "union/surface_union.h"

#include <array>
#include <optional>

namespace mr::surface_union {

/// The faces of `b` turn outward: its signed volume is not negative.
bool faces_outward(const Body& b);

/// Two faces of `b` that meet other than along what they share (corners count as shared
/// when their ids or their positions are equal): the first found with the smallest first
/// face, or none. `edges` is b's edge table; `outward` as faces_outward(b). The convex
/// shortcuts need a closed, manifold body; on any other every pair is tested.
std::optional<std::array<int, 2>> self_intersection(const Body& b, const EdgeTable& edges, bool outward);

/// The same, building the edge table and the orientation.
std::optional<std::array<int, 2>> self_intersection(const Body& b);

}  // namespace mr::surface_union
