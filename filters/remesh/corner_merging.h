// Corners joined by a line much shorter than the local size become one output point. No element
// of that size fits along such a line (two corners 0.0009 apart at a target of 0.016, where a
// CAD edge ends beside an intersection line: one face of 6.7 degrees), and the line is below
// what the regrid can show anyway.
#pragma once

#include "features/feature_lines.h"
#include "remesh/face_rings.h"
#include "remesh/size_field.h"
#include "remesh/surface_locator.h"

#include <vector>

namespace mr::remesh {

/// A line shorter than this times the size at its ends joins its end corners.
constexpr double kTinyLine = 0.2;

struct CornerMerging {
  std::vector<int> representative;  ///< per input vertex: the corner whose point it takes (itself if not merged)
  std::vector<char> dropped_line;   ///< per line: a tiny line inside a merged group (no points)
  std::vector<char> dropped_patch;  ///< per patch: bounded by dropped lines only (it shrinks to the point)
  int merged_corners = 0;           ///< corners that took another corner's point

  /// Every corner keeps its own point.
  static CornerMerging none(const features::Result& features, const Surface& surface);
};

/// Groups of corners joined by tiny open lines. A group is merged only when every patch meets it
/// along one run of its border (else the patch would be pinched at the point), when no longer
/// line joins two of its corners, and when all its corners lie within kTinyLine x size of the
/// one that represents it (the corner with the most lines, then the lowest index).
/// `rings`: the faces around each vertex of `surface`.
CornerMerging merge_close_corners(const features::Result& features, const Surface& surface, const FaceRings& rings,
                                  const SizeField& size);

}  // namespace mr::remesh
