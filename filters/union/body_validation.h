// Checks each body before any work: finite, non-degenerate, closed, manifold,
// consistently oriented and not crossing itself; inward-oriented bodies are flipped
// (returned count).
#pragma once

#include "union/surface_union.h"

#include <vector>

namespace mr::surface_union {

/// \throw InvalidInput / TopologyError naming the body. Flips inward bodies in place.
/// With `self_intersections`, a body that crosses itself is refused too.
int validate_bodies(std::vector<Body>& bodies, bool self_intersections = true);

}  // namespace mr::surface_union
