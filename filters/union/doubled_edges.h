// Two sheets of the union that touch along a segment, and meet again at both of its ends
// (another body's face there, or a third body crossing the segment), leave one fan of
// faces around each end: the segment is then two edges between the same two vertices,
// which an indexed mesh cannot tell apart (four faces on one edge).
#pragma once

#include "union/surface_union.h"

namespace mr::surface_union {

/// Intersection-line edges with more than two faces (vertex pairs, lower first). Only
/// there do sheets of different bodies meet.
std::vector<std::array<int, 2>> doubled_line_edges(const Result& r);

/// Splits every copy of each `doubled` edge at its middle, with a vertex of its own
/// (coincident, one per sheet), so that every edge has two faces; the sheets then touch
/// where their vertices coincide, as elsewhere in the output (read back as one body, they
/// do not cross: self_intersection.h counts coincident corners as shared). Copies
/// are the face pairs `partner` gives (per face side 3*f+z: the side across it, or -1);
/// edges whose sides do not pair up are left as they are. New faces take their parent's
/// `cut` flag. Returns the number of edges split.
int split_doubled_edges(Result& r, std::vector<char>& cut, std::vector<int> partner,
                        const std::vector<std::array<int, 2>>& doubled);

}  // namespace mr::surface_union
