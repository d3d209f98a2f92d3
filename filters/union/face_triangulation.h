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

/// A crossing of two constraint segments inside a face, found while triangulating it:
/// to go into the point table on the lines of both segments (u, w) and (c, d).
struct FaceCrossing {
  QPoint point;
  int u, w, c, d;
};

/// One face's triangulation before its crossings are in the point table: triangle
/// corners are table indices, or -1 - k for crossings[k].
struct FaceTriangles {
  std::vector<std::array<int, 3>> triangles;
  std::vector<FaceCrossing> crossings;
};

/// Triangulates the face with corners `corners` cut by `c` (triangles oriented as the
/// face) without changing `points`: many faces can be triangulated at once.
void triangulate_face(const PointTable& points, const std::array<int, 3>& corners, const FaceConstraints& c,
                      FaceTriangles& out);

/// Inserts the face's crossings into `points` (in the order found, so faces committed in
/// a fixed order give the same table whatever ran in parallel) and appends its
/// triangles to `out` in table indices.
void commit_face(PointTable& points, FaceTriangles& face, std::vector<std::array<int, 3>>& out);

/// Both steps at once, for one face. Returns the number of triangles appended.
int triangulate_face(PointTable& points, const std::array<int, 3>& corners, const FaceConstraints& c,
                     std::vector<std::array<int, 3>>& out);

}  // namespace mr::surface_union
