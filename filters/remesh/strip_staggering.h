// Points of the second line along a thin strip (the rim of a thin plate), placed against those
// of the line across it. Discretised on its own, a line gets its points right across from those
// of the other side (same length, same sizes): the one layer of faces between them is then made
// of right triangles as flat as the strip is narrow, atan(width / segment). Placed where the
// points kStagger of the way along the other side's segments project onto it, a face's smallest
// angle becomes atan(width / ((1 - kStagger) x segment)).
#pragma once

#include "common/tri_mesh.h"

#include <vector>

namespace mr::remesh {

/// Half-way would double the angle, but then both edges across the strip are half a segment
/// long: on cad/blade.off at 1% the rims' angles went 1.09 -> 2.17 degrees and the edges within
/// [0.7, 1.4] x target 95.1% -> 92.7%. At 0.28 the longer edge across keeps 0.72 x segment (in
/// range, as the one diagonal of the aligned layout was) and the angle is 1.51 degrees.
constexpr double kStagger = 0.28;

/// Only lines of at least this many elements are staggered: on a short strip between corners (a
/// sliver of a scan) the corners set the angles, and moving its one or two points towards the
/// other side's cost armadillo's worst angle 7.0 -> 2.7 degrees.
constexpr int kMinStaggeredSegments = 3;

/// Positions of a line's points, as normalised arc lengths (in elements; `cumulative` holds those
/// of the polyline's vertices), ends included: the projections of `opposite_points` within
/// `reach` of the polyline, gaps longer than 1.5 elements filled evenly, and no point closer than
/// a quarter element to the one before it or to the end. Empty if no opposite point is in reach.
std::vector<double> staggered_positions(const std::vector<Point3>& polyline, const std::vector<double>& cumulative,
                                        const std::vector<Point3>& opposite_points, double reach);

}  // namespace mr::remesh
