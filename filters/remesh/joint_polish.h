// A joint search over the points around a face that stays under the goal. The passes before it
// move one point at a time (or a line point with one partner) and keep a move only if that
// point's faces get better; where two lines run a few thousandths apart, or three meet, the
// faces there are balanced so that any single move makes a neighbour worse, and they stay a
// degree or less under 30 (the 50-sphere cluster's necks). Moving the whole neighbourhood
// together lifts them: a compass search over every movable point of the face and of its ring at
// once, each line point sliding along its input polyline, each free point moving in its tangent
// plane and projected back onto the input.
#pragma once

#include "remesh/line_sliding.h"
#include "remesh/output_mesh.h"
#include "remesh/surface_locator.h"

#include <array>
#include <vector>

namespace mr::remesh {

/// For each face whose smallest angle off the wedge tips (wedge_tips.h) is under `goal_rad`, in
/// face order: searches the places of the movable points around it (slidable points of
/// `paths`, free points of `movable` with a host face) that bring every corner of their faces,
/// off the tips, nearest to the goal and a little beyond. The search's result is kept only
/// where the smallest angle there, off the tips, reaches the goal, no tip narrows and no face
/// turns by more than 60 degrees; otherwise the points go back. `paths` and the hosts follow
/// the moves. Only faces with a corner in `near` (all when empty) are looked at; faces more
/// than 10 degrees under the goal are not (no place of their points mends them: a plate's rim,
/// an input's wedge). Returns the points moved, in the order they moved (each once per search).
std::vector<int> polish_jointly(OutputMesh& out, std::vector<LinePath>& paths,
                                const std::vector<std::array<int, 2>>& feature_edges, const SurfaceLocator& locator,
                                const std::vector<char>& movable, double goal_rad,
                                const std::vector<char>& near = {});

}  // namespace mr::remesh
