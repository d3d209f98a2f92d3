// The doubles of a crossing point (its exact rational coordinates truncated towards
// zero) from integers on the stack: most crossings need nothing else, and GMP's
// integers cost several times the arithmetic at these sizes.
#pragma once

#include "union/exact.h"

#include <array>

namespace mr::surface_union {

/// Sets `d` to the truncated coordinates of the crossing `recipe` describes and
/// returns true; returns false, leaving it to exact rationals, where the integers do
/// not fit or the leading bits of a quotient cannot decide its truncation (within a
/// few units of its 64th bit of a 53-bit boundary).
bool truncated_crossing_on_stack(const QPoint::Recipe& recipe, std::array<double, 3>& d);

}  // namespace mr::surface_union
