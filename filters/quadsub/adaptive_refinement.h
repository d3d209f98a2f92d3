// Adaptive interpolatory quad subdivision: only some faces are refined at each level,
// the mesh stays balanced (faces sharing an edge differ by at most one level) and
// conforming (hanging edge points are closed by transition faces, so there are no cracks).
// Every new point is the point the uniform scheme (interpolatory_subdivision.h) puts there.
#pragma once

#include "quadsub/interpolatory_subdivision.h"

#include <array>
#include <vector>

namespace mr::quadsub {

enum class RefineFaces {
  All,             ///< every face at every level: the uniform scheme
  Selected,        ///< the selected input polygons, and at later levels their children
  ErrorAbove,      ///< faces whose face point lies farther than the threshold from their bilinear centre
};

struct AdaptiveParams {
  RefineFaces refine = RefineFaces::Selected;
  /// With ErrorAbove: a face is refined when |face point - mean of its corners| exceeds this
  /// fraction of the input's bounding-box diagonal. > 0.
  double error_threshold = 0.001;
  /// Work only, not the result: levels below 1 are first computed for the input quads within
  /// this many rings (plus the stencil margin) of the first refined faces, and the region is
  /// widened (2r + 2) whenever a face beyond it must be split. >= 0.
  int initial_region_rings = 2;
};

struct AdaptiveResult {
  QuadMesh mesh;                              ///< quads; points of the input first, unmoved
  std::vector<std::array<int, 3>> triangles;  ///< transition triangles (counter-clockwise), same points
  std::vector<int> quad_level;                ///< subdivision level of each quad (0 = input)
  std::vector<int> triangle_level;            ///< level of the unrefined face each triangle closes
  int vertices_in = 0, faces_in = 0;
  int extraordinary_vertices = 0;
  int crease_edges_in = 0;
  int cusps = 0;
  int levels = 0;                             ///< highest level reached
  std::vector<int> refined_per_level;         ///< faces split at level l (0 = input faces)
  int balance_refinements = 0;                ///< of those, split only to keep the mesh balanced or closed
  int transition_faces = 0;                   ///< quads and triangles closing hanging edge points
  int hierarchy_faces = 0;                    ///< quads computed over all levels (work done)
  int region_restarts = 0;                    ///< times the computed region had to be widened
};

/// Refines `params.iterations` levels; at each level the faces of the previous level that
/// pass the criterion are split into four. Level 1 is computed in full; deeper levels only
/// near the refined faces, wide enough that every stencil is the uniform one. A face is split only after its coarser edge
/// neighbours (balance), and an unsplit face whose four neighbours are split is split too.
/// RefineFaces::All runs `subdivide` (every face at level `levels`).
/// `selected_polygons[i]` marks polygon i (read with RefineFaces::Selected; a split non-quad
/// polygon passes the mark to all its quads).
/// \throw InvalidInput on bad parameters (as `subdivide`, plus a threshold <= 0 or a selection
///        of the wrong size); TopologyError as `subdivide`.
AdaptiveResult subdivide_adaptive(const std::vector<Point3>& points, const std::vector<std::vector<int>>& polygons,
                                  const EdgeList& marked_creases, const std::vector<char>& selected_polygons,
                                  const Params& params, const AdaptiveParams& adaptive);

}  // namespace mr::quadsub
