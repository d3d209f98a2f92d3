// A front that could not close leaves a few open sides, and may pinch a point, in thin or
// tightly bent parts of a scan. Rather than meshing the whole patch again with smaller elements
// (which shortens every edge of it, and on a one-patch input costs a full meshing), the patch's
// faces around the trouble spots are taken out and only that hole is meshed again, smaller.
#pragma once

#include "remesh/advancing_front.h"
#include "remesh/output_mesh.h"

#include <vector>

namespace mr::remesh {

/// Removes the faces of `patch` with a corner within `radius` of an end of `open_sides` or of a
/// `spot` point (pinched points, corners of oversized faces), and returns the front of the hole left behind: the removed faces' sides that
/// border a remaining face or lie on the patch's `initial_front`, and the open sides still
/// bordering a remaining face. Empty (and nothing removed) when there is no trouble spot.
std::vector<FrontSide> open_hole_around(OutputMesh& out, int patch, const std::vector<FrontSide>& initial_front,
                                        const std::vector<FrontSide>& open_sides, const std::vector<int>& spots,
                                        double radius);

/// Points of the faces of `patch` whose centroid lies farther than `max_distance` from the input
/// faces of the patch: a front that bridged a groove or cut across a tip; ascending.
std::vector<int> stray_face_points(const OutputMesh& out, int patch, const SurfaceLocator& locator, double max_distance);

/// Points of the faces of `patch` with a side longer than `max_length`, or longer than
/// `needle_length` with an angle under `needle_angle` (radians): what a stuck front closes, a fan
/// or an ear across a loop of far-apart points; ascending.
std::vector<int> oversized_face_points(const OutputMesh& out, int patch, double max_length, double needle_length = 0,
                                       double needle_angle = 0);

/// Faces of `patch` with a point on `front` (the ring around a hole).
std::vector<int> faces_around(const OutputMesh& out, int patch, const std::vector<FrontSide>& front);

/// Edges with more than two faces or two faces of the same orientation, over the whole mesh.
int bad_edges(const OutputMesh& out);

}  // namespace mr::remesh
