// Wedge tips: a face corner whose two sides both lie on feature lines, at an angle under
// kWedgeBoundDeg. One face fills the wedge between those lines there, and its angle at that
// corner is the wedge's whatever the mesh does, as long as it keeps the lines. Measures of the
// mesh's own quality, and moves that optimise it, leave such corners out (a line point beside a
// wedge tip could otherwise never slide: its star's smallest angle is the tip's, fixed).
#pragma once

#include "remesh/output_mesh.h"

#include <cstdint>
#include <unordered_set>

namespace mr::remesh {

/// The quality goal (issue #2's and #4's 30 degrees): narrower wedges are measured apart.
constexpr double kWedgeBoundDeg = 30.0;
constexpr double kWedgeBoundRad = kWedgeBoundDeg * 3.14159265358979323846 / 180.0;

/// Corner `at` of a face, with the face's other corners `b` and `c`, `angle` radians there, is a
/// wedge tip. `feature_keys`: the feature edges' OutputMesh::edge_key.
inline bool is_wedge_tip(double angle, int at, int b, int c, const std::unordered_set<std::uint64_t>& feature_keys) {
  return angle < kWedgeBoundRad && feature_keys.count(OutputMesh::edge_key(at, b)) &&
         feature_keys.count(OutputMesh::edge_key(at, c));
}

}  // namespace mr::remesh
