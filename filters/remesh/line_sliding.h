// Constrained smoothing of feature-line points: a line point slides along its input polyline,
// between its two neighbours on the line, to where the smallest angle of its faces is largest.
// Lines are discretised before the patches and know nothing of them; where two lines converge
// (a crease tip) or run side by side (a thin rim, a noisy scan's twin ridges) the points of the
// two lines face each other and the faces between them are needles. Sliding staggers them.
// The point stays on the input ridge exactly and the move is kept only if it raises the
// smallest angle around the point, so the mesh's minimum angle never drops.
#pragma once

#include "remesh/output_mesh.h"

#include <vector>

namespace mr::remesh {

/// One discretised feature line: the input polyline it follows and its output points in order.
struct LinePath {
  std::vector<Point3> polyline;   ///< input vertices along the line (a closed line repeats its first)
  std::vector<int> segment_host;  ///< an input face on each polyline segment (host of points there)
  std::vector<int> points;        ///< output points, first to last (a closed line repeats its first)
  std::vector<double> arc;        ///< arc length of each output point along the polyline
  /// Points that may slide: false for the ends and for points another line shares.
  std::vector<char> slidable;
};

/// Moves line points along their lines where that raises the smallest angle of their faces
/// below `worse_than_rad`, and where it lifts a smallest angle below `goal_rad` to at least
/// `goal_rad` (the rest are left alone: the lines keep their even spacing); `paths` follow
/// the moves. Returns the points that moved, in the order they moved.
/// A point tries sixths of the arc between its neighbours, then twelfths, then small steps
/// around its own place. Where none lifts its faces to the goal, it slides together with a
/// slidable point of another line on one of its faces (at a corner where three lines leave, the
/// face between two of them is bounded by both first segments); such a pair is kept only where
/// the smallest angle off the wedge tips around both points reaches the goal.
/// With `short_of_goal`, a point between the two bounds that does not reach the goal alone takes
/// the place of its own with the largest gain short of it (at least half a degree), else the
/// pair of places with a partner that reaches the goal or raises the smaller of their rings'
/// angles off the tips most (by as much); the caller asks for that only once the plain sweeps are
/// over, so that it stands in no later slide's way.
/// Where the smallest angle around the point is a wedge tip's between `feature_edges`
/// (wedge_tips.h), which no slide along a straight line changes, the smallest angle off the tips
/// decides, or no point beside a tip would move.
std::vector<int> slide_line_points(OutputMesh& out, std::vector<LinePath>& paths,
                                   const std::vector<std::array<int, 2>>& feature_edges, double worse_than_rad,
                                   double goal_rad, bool short_of_goal = false);

}  // namespace mr::remesh
