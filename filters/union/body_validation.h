// Checks each body before any work: finite, non-degenerate, closed, manifold and
// consistently oriented; inward-oriented bodies are flipped (returned count).
#pragma once

#include "union/surface_union.h"

#include <vector>

namespace mr::surface_union {

/// \throw InvalidInput / TopologyError naming the body. Flips inward bodies in place.
int validate_bodies(std::vector<Body>& bodies);

}  // namespace mr::surface_union
