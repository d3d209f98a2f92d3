// How many slivers the union itself left: output faces under an angle that are worse than
// the input face they lie in. CAD inputs bring their own needles, which no step may be
// blamed for; this count is the part of the output's slivers that the cut made and the
// sliver step could not mend.
#pragma once

#include "union/surface_union.h"

#include <vector>

namespace mr::surface_union {

/// The output faces of `r` (indices, ascending) whose smallest angle is below `angle_deg` and below the smallest
/// angle of their input face (`r.face_source`, an index into all `bodies`' faces in order).
/// After the sliver step a face's source is the input face its slot came from, within
/// the deviation bound of it: the count then compares with a neighbour's shape at worst.
/// A flat flip's two faces lie across both old ones and take the worse one's source.
std::vector<int> find_slivers_left(const Result& r, const std::vector<Body>& bodies, double angle_deg);

}  // namespace mr::surface_union
