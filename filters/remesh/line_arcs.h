// Places along a discretised feature line by arc length: where a line point slides to, and
// which points may slide. Shared by the slides of single points (line_sliding.h) and the
// joint search around a face (joint_polish.h).
#pragma once

#include "remesh/line_sliding.h"

#include <array>
#include <vector>

namespace mr::remesh {

/// A place on a line's input polyline and the polyline segment it lies on.
struct ArcPlacement {
  Point3 point;
  int segment = 0;
};

/// Arc length along the path's polyline at each of its vertices.
std::vector<double> cumulative_arc(const LinePath& path);

/// The place at arc length `s` (clamped to the polyline), given the path's cumulative_arc.
ArcPlacement at_arc(const LinePath& path, const std::vector<double>& cumulative, double s);

/// Per output point (`nv` of them): the path and index where it may slide, or {-1, -1}.
std::vector<std::array<int, 2>> slidable_slots(const std::vector<LinePath>& paths, size_t nv);

}  // namespace mr::remesh
