// One orientation across each connected part of a triangle mesh: faces are flipped so that the
// two faces on every manifold edge run it in opposite directions. Cores whose geometric tests
// rely on face normals (a host face "agrees" with a point's normal) run on such a copy of an
// input whose faces a careless export flipped here and there.
#pragma once

#include "common/tri_mesh.h"

namespace mr {

struct CoherentOrientation {
  int flipped = 0;    ///< faces flipped
  int conflicts = 0;  ///< manifold edges still run one way by both faces (a non-orientable part)
};

/// Manifold edges whose two faces run them the same way.
int count_misoriented_edges(const TriMesh& mesh);

/// Flips faces of `mesh` (compact) so that each part connected across manifold edges has one
/// orientation: the one the larger area of its faces had.
CoherentOrientation orient_coherently(TriMesh& mesh);

}  // namespace mr
