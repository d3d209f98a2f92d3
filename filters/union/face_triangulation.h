// Re-triangulation of one cut face in its own plane: the intersection segments
// (split where they meet) become edges of a constrained triangulation of the face,
// improved towards Delaunay away from the constraints. All decisions are exact
// predicates on the rational points, so faces meeting along an edge or along an
// intersection segment put exactly the same vertices on it.
#pragma once

#include "union/point_table.h"
#include "union/soup.h"

#include <array>
#include <vector>

namespace mr::surface_union {

/// Appends to `out` the triangles (point-table indices, oriented as the face) of the
/// face with corners `corners` cut by `c`. New crossing points go into `points`.
/// Returns the number of triangles appended.
int triangulate_face(PointTable& points, const std::array<int, 3>& corners, const FaceConstraints& c,
                     std::vector<std::array<int, 3>>& out);

}  // namespace mr::surface_union
