// A body that crosses itself has no inside that the union could be decided by. Found
// before any work: bodies star-shaped about their vertex centroid (convex ones, blobs)
// cannot cross themselves; on the others the face pairs whose boxes overlap
// (face_clearance's grid) get the exact triangle test of face_clearance.h, but pairs that
// share only a vertex where the surface is locally convex or its star is one to one in a
// coordinate projection.
#pragma once

#include "common/edge_table.h"
#include "union/face_clearance.h"
#include "union/surface_union.h"

#include <array>
#include <optional>

namespace mr::surface_union {

/// The faces of `b` turn outward: its signed volume is not negative.
bool faces_outward(const Body& b);

/// Two faces of `b` that meet other than along what they share (corners count as shared
/// when their ids or their positions are equal), lower face first: the first found
/// scanning the faces in order, or none. `edges` is b's edge table; `outward` as
/// faces_outward(b). The shortcuts need a closed, manifold body; on any other every pair
/// is tested.
std::optional<std::array<int, 2>> self_intersection(const Body& b, const EdgeTable& edges, bool outward);

/// The same, building the edge table and the orientation.
std::optional<std::array<int, 2>> self_intersection(const Body& b);

/// self_intersection in parts, to share one body's check out among threads: built once
/// (edge table, orientation, the shortcuts, the face grid), then scanned in ranges of
/// first faces, on any threads at once, each with its own marks.
class SelfIntersectionScan {
public:
  explicit SelfIntersectionScan(const Body& b);
  /// Two faces that meet (lower first), the first found scanning first faces in [begin, end)
  /// in order: scans of consecutive ranges give self_intersection's pair from the first
  /// range that finds one.
  std::optional<std::array<int, 2>> scan(int begin, int end, FaceGrid::Marks& marks) const;

private:
  const Body& b_;
  bool skip_ = false;          // star-shaped: no two faces cross
  std::vector<char> convex_;   // per vertex: faces meeting only there cannot cross
  std::optional<FaceGrid> grid_;
};

}  // namespace mr::surface_union
