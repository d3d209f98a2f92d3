// A body that crosses itself has no inside that the union could be decided by. Found
// before any work: a grid over the body's face boxes, then the exact triangle test of
// face_clearance.h on the pairs whose boxes overlap.
#pragma once

#include "union/surface_union.h"

#include <array>
#include <optional>

namespace mr::surface_union {

/// Two faces of `b` that meet other than along what they share (corners count as shared
/// when their ids or their positions are equal): the first found with the smallest first
/// face, or none.
std::optional<std::array<int, 2>> self_intersection(const Body& b);

}  // namespace mr::surface_union
