// The union is exact until its points are rounded to doubles. Crossings closer than a
// unit in the last place (bodies that nearly coincide: a symmetric part and its copy
// turned by a floating-point half turn) then land on one place, or a few units apart:
// an edge between them has no length or next to none, and its faces degenerate into
// needles whose smallest angle is 1e-13 degrees, or no area at all.
#pragma once

#include "union/surface_union.h"

#include <array>
#include <cmath>

namespace mr::surface_union {

/// Merges the two ends of edges that rounding left within 4 units in the last place of the
/// largest coordinate (per coordinate; 0 included), shortest first, where the link
/// condition holds (the ends share only the corners opposite the edge). The edge's two
/// faces go. An edge without length changes no other face's shape; otherwise the faces
/// that move (by those few units) are checked exactly against every face near them first:
/// none may turn over, degenerate (unless it had no area already) or cross another. Line
/// flags of the two sides that become one are joined. Faces, `cut` and line flags are
/// compacted, and vertices no face uses dropped. Only cut faces are looked for such edges
/// (an input face has distinct corners, so one end at least is a crossing). Returns the
/// number of vertices merged away; an edge whose ends fail the checks is left as it is.
int merge_rounded_together(Result& r, std::vector<char>& cut);

/// 4 units in the last place of the largest coordinate of `r`: how far apart rounding to
/// doubles can put points that the exact union has at one place or on one line.
double rounding_slack(const Result& r);

/// a and b are within `slack` of each other in every coordinate.
inline bool within_slack(const std::array<double, 3>& a, const std::array<double, 3>& b, double slack) {
  return std::fabs(a[0] - b[0]) <= slack && std::fabs(a[1] - b[1]) <= slack && std::fabs(a[2] - b[2]) <= slack;
}

}  // namespace mr::surface_union
