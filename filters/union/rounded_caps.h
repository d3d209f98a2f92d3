// Rounding the exact union to doubles can also flatten a face onto one of its sides: its
// third corner (the apex) lands within a few units in the last place of the line through
// the other two, between them. The face has next to no area and an angle of ~180°; where
// the apex rounded across that side, the face overlaps its neighbour and the surface
// crosses itself there (nearly coincident sheets: a body and its copy scaled about one of
// its vertices).
#pragma once

#include "union/surface_union.h"

namespace mr::surface_union {

/// Removes such caps among the cut faces (apex within rounding_slack() of the long side's
/// line, strictly between its ends), keeping the face count:
/// - a cap alone on its long side: the neighbour across that side is split at the apex (the
///   two halves cover the neighbour and the cap);
/// - caps on both sides of one long side: both go, and the two chains of sides left along
///   it are zipped, each side that holds a corner of the other chain split at it.
/// The new faces must keep their parents' turn strictly (projection across the parent's
/// largest normal component), add no edge the surface has already, and meet no face that
/// the faces they replace did not meet (exact); otherwise the cap stays. Sides along the
/// long side are line edges where it or the side they replace was. `cut` and
/// Result::face_source follow the new faces.
/// - Two caps whose apexes rounded to one place (or within rounding_slack()): their long
///   side is flipped to join the apexes, an edge without length or next to none; `flipped` (if given) counts them, and
///   merge_rounded_together() must run again to merge its ends.
/// Returns the number of caps removed (a flipped pair counting as one).
int split_rounded_caps(Result& r, std::vector<char>& cut, int* flipped = nullptr);

}  // namespace mr::surface_union
