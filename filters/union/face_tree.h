// A bounding-box tree over a fixed triangle surface, for the distance of points from it:
// the sliver step keeps every face it makes near the surface the cut made. A tree, not
// a grid: the long CAD needles of box.STL would fill a grid's cells.
#pragma once

#include "union/triangle_distance.h"
#include "union/vec3.h"

#include <array>
#include <vector>

namespace mr::surface_union {

class FaceTree {
public:
  FaceTree() = default;
  /// Copies the corners of faces `which` (indices into `faces`): the tree does not follow
  /// later changes of the mesh.
  FaceTree(const std::vector<V3>& vertices, const std::vector<std::array<int, 3>>& faces,
           const std::vector<int>& which);
  bool empty() const { return nodes_.empty(); }

  /// Faces to try first: those that ended the last few searches (samples close together
  /// are mostly near the same faces). Start from a default-constructed one.
  struct Recent {
    std::array<int, 4> faces{-1, -1, -1, -1};
    size_t next = 0;
  };
  /// Distance from p to the nearest face, with two shortcuts: the search ends at the first
  /// face within `enough` (the result is then at most `enough`), and faces beyond `limit`
  /// are not looked at (the result is then larger than `limit`). Otherwise the result is
  /// the exact distance, whatever `recent` holds.
  double distance(const V3& p, double enough, double limit, Recent* recent = nullptr) const;

private:
  struct Node {
    V3 lo, hi;
    int left = -1, right = -1;  // children, or -1 in a leaf
    int first = 0, count = 0;   // a leaf's triangles
  };
  int build(int first, int count, std::vector<int>& order, const std::vector<std::array<V3, 3>>& corners,
            const std::vector<V3>& centroids);
  std::vector<Node> nodes_;
  std::vector<PreparedTriangle> triangles_;  // in leaf order
};

}  // namespace mr::surface_union
