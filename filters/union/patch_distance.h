// Whether a move keeps the surface near where it was: the sliver step bounds how far it
// moves the union. The distance of one vertex from the new faces is not enough where a
// star folds over (thin fins of scanned blobs: rabbit.obj), so the two patches are
// compared, each sampled against the other.
#pragma once

#include "union/vec3.h"

#include <array>
#include <vector>

namespace mr::surface_union {

using Triangle = std::array<V3, 3>;

/// Every sample point of each face of `a` (centroid and edge midpoints) lies within
/// `limit` of some face of `b`,
/// and the other way round. For patches that share their boundary and differ by one
/// small move, this is their Hausdorff distance against the limit, up to the sampling.
bool patches_within(const std::vector<Triangle>& a, const std::vector<Triangle>& b, double limit);

}  // namespace mr::surface_union
