// The union is exact until its points are rounded to doubles. Two crossings closer
// than a unit in the last place (bodies that nearly coincide: a symmetric part and its
// copy turned by a floating-point half turn) then land on one place, and an edge
// between them has no length: its two faces degenerate.
#pragma once

#include "union/surface_union.h"

namespace mr::surface_union {

/// Merges the two ends of every edge whose ends have the same coordinates, where the
/// link condition holds (the ends share only the corners opposite the edge): the two
/// faces of the edge go, which have no area and cover nothing their neighbours do not;
/// no other face changes shape, so nothing can come to cross. Line flags of the two
/// sides that become one are joined. Faces, `cut` and line flags are compacted, and
/// vertices no face uses dropped. Only cut faces are looked for such edges (an input
/// face has distinct corners, so one end at least is a crossing). Returns the number of
/// edges merged; an edge whose ends fail the link condition is left as it is.
int merge_zero_length_edges(Result& r, std::vector<char>& cut);

}  // namespace mr::surface_union
