// An exact translation that brings a mesh lying far from the origin next to it.
// Far away (UTM coordinates, a CAD part placed in a plant's frame) a double keeps
// fewer bits below the features' size, and tolerances scaled by the feature size
// fail on rounding noise; near the origin the same input is well conditioned.
#pragma once

#include "common/tri_mesh.h"

namespace mr {

/// Per axis: the box's lower corner where the whole box lies farther out on the positive
/// side than it is long, its upper corner where it lies that far out on the negative side,
/// else 0. Subtracting it from any coordinate inside the box is exact (every coordinate is
/// a multiple of the corner's unit in the last place and no larger), and adding it back to
/// a shifted input point gives that point again bit for bit.
Point3 exact_shift_towards_origin(const Box3& box);

/// Moves every vertex of `m` by -shift (exact for vertices inside the box the shift was made for).
void shift_vertices(TriMesh& m, const Point3& shift);

}  // namespace mr
