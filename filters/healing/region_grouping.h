// Step 7 of the healing: feature lines along the welded patch borders and
// regions of patches bounded by them.
#pragma once

#include "healing/soup.h"

#include <array>
#include <vector>

namespace mr::healing {

struct Regions {
  std::vector<std::array<bool, 3>> feature;  ///< per face side
  std::vector<int> group;                    ///< per face, numbered by first face
  int feature_edges = 0;
  int groups = 0;
};

/// A seam is a manifold edge between two faces of different patches, or one
/// listed in `welded` (vertex pairs of the soup). A seam whose face normals
/// differ by more than `feature_angle_deg` is a feature line. Groups grow
/// across every manifold edge that is not a feature line.
Regions group_patches(const Soup& soup, const EdgeTable& edges, const std::vector<std::array<int, 2>>& welded,
                      double feature_angle_deg);

}  // namespace mr::healing
