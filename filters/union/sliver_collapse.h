// Surface improvement after the cut: faces with a small angle are removed by
// collapsing their shortest edge into one of its ends, when no face normal flips,
// the worst angle around improves, the intersection lines keep their shape, the
// surface moves less than a bound and no new face crosses another (checked exactly
// for every move before it is applied).
#pragma once

#include "common/side_worker.h"
#include "union/surface_union.h"

namespace mr::surface_union {

/// Collapses slivers of `r` in place (vertices, faces, line_edge, compacted);
/// returns the number of collapses. Only faces with `cut[f]` (made by the cut) are
/// treated; slivers the input already had are left as they are, but for those a line
/// bent onto a crease vertex reshapes (they are then treated too) and for the flat flips
/// below.
/// `max_deviation` bounds the distance of the result from the cut's surface, all moves
/// together (fraction of the bbox diagonal); `max_volume_change` bounds the total volume
/// change of all moves (fraction of the volume).
/// `helper` (may be null) takes each move's crossing check beside its other checks, and
/// the tree of the cut's surface beside the setup; the result is the same without it.
/// Many slivers (4000 or more) are treated in two halves of the surface at once, each
/// changing only faces strictly on its side of a plane, then over the whole surface
/// where they left slivers; `parts` (may be null) gets 2 then, else 1. The result does
/// not depend on the number of threads.
/// Before its checked moves the step flips edges between two of the input's own faces
/// in one plane where one is a sliver (Lawson's flips, which move nothing; the faces stay
/// the input's); `flat_flips` (may be null) gets their number.
int collapse_slivers(Result& r, const std::vector<char>& cut, double sliver_angle_deg, double max_deviation,
                     double max_volume_change, SideWorker* helper = nullptr, int* parts = nullptr,
                     int* flat_flips = nullptr);

/// Smallest face angle of a mesh, degrees.
double min_angle_deg(const std::vector<std::array<double, 3>>& v, const std::vector<std::array<int, 3>>& f);

}  // namespace mr::surface_union
