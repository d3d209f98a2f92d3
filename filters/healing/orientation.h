// Step 5 of the healing: one orientation across the welded patches.
#pragma once

#include "healing/soup.h"

namespace mr::healing {

struct Orientation {
  int faces_flipped = 0;
  int conflicts = 0;  ///< manifold edges still inconsistent (a non-orientable part)
};

/// Flips faces so that every manifold edge is used in opposite directions by
/// its two faces. Closed parts end up with outward normals when `outward`;
/// open parts keep the orientation most of their faces had.
Orientation orient_consistently(Soup& soup, bool outward);

}  // namespace mr::healing
