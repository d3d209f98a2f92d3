// Inside/outside: the outer surface of the arrangement of cut bodies, collected by a
// flood fill from an extreme face of each connected piece. Where several faces meet
// at an intersection edge, the fill continues into the face met first when turning
// about the edge from the current face towards its outside (the visible neighbour).
#pragma once

#include "union/point_table.h"
#include "union/soup.h"

#include <array>
#include <vector>

namespace mr::surface_union {

struct Classification {
  std::vector<char> kept;        ///< per sub-face: on the outer surface
  std::vector<int> partner;      ///< per kept face side 3*s+z: the side 3*s'+z' across it
  std::vector<char> line_edge;   ///< per face side: the edge joins faces of different bodies
  int pieces = 0;                ///< edge-connected pieces of the arrangement
  int pieces_inside = 0;         ///< pieces enclosed by another body (removed whole)
  int orientation_conflicts = 0; ///< fill steps into a face not oriented against the current one
  int open_sides = 0;            ///< kept face sides with no face across (must stay 0)
};

/// \param sub sub-faces (point indices), \param sub_body their bodies, \param sub_face the
/// input face each was cut from, \param dropped sub-faces already excluded (coplanar
/// duplicates), \param soup the input bodies (for the point-in-body test of pieces that
/// touch no other piece), \param kept_copy_body for a sub-face lying on a coplanar face of a
/// lower body with the same orientation (a copy), that body (else -1).
Classification classify_outside(const PointTable& points, const std::vector<std::array<int, 3>>& sub,
                                const std::vector<int>& sub_body, const std::vector<int>& sub_face,
                                const std::vector<char>& dropped, const std::vector<int>& kept_copy_body,
                                const Soup& soup);

}  // namespace mr::surface_union
