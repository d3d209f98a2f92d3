// Wedge relaxing (opt-in): where two feature lines leave a point at an angle under 30 degrees,
// the face filling the wedge keeps that angle whatever the mesh does, as long as it keeps both
// lines (wedge_tips.h). Letting the two lines share their first segment takes the wedge away:
// their first points become one, halfway between them on the surface, and the next face between
// the lines sees them at about twice the angle (2 atan(2 tan(a/2)): 26 -> 50, 19.7 -> 38 degrees).
// Each merge moves a line by at most the two points' distance (under 0.6 x the size), half of it
// where they meet halfway, the usual case: below what the elements could show anyway.
// Lines that pass close without meeting are the same problem without a tip, and the same merge
// (or a point joining the other line's segment) makes them meet: close_line_gaps.
#pragma once

#include "remesh/line_sliding.h"
#include "remesh/output_mesh.h"
#include "remesh/size_field.h"
#include "remesh/surface_locator.h"

#include <array>
#include <vector>

namespace mr::remesh {

/// The first points of two lines may merge where they are at most this far apart, x the size
/// at the tip (a wedge under 30 degrees is at most 0.52 x the size wide one element from its tip).
constexpr double kRelaxWidth = 0.6;

/// Points of two lines that do not meet there may merge where they are at most this far apart,
/// x the smaller size at them: in a strip that narrow, between line segments of the size, no face
/// reaches 27 degrees.
constexpr double kCloseGap = 0.25;

/// A point snaps onto another line's segment only opposite its middle part: this fraction of the
/// segment at either end is left to the merge of two points.
constexpr double kSnapFrom = 0.15;

/// Merges the two points beside each wedge tip of `paths` (each slidable, a corner, or a junction
/// that several paths hold, joined by a face edge that is no feature edge, at most kRelaxWidth x
/// the size apart) into one point that every line through them shares (a corner if either was
/// one): at the surface point halfway between them, else at one of them (a junction's own place
/// only), where that raises the smallest angle of their faces, the
/// link condition holds and no face turns by more than acos(0.7). The merged point no longer
/// slides; a wedge still under 30 degrees beyond it is relaxed again in a later sweep. `paths`
/// and `feature_edges` follow; the removed points stay in `out.points`, used by no face. Returns
/// the merged points.
std::vector<int> relax_wedge_tips(OutputMesh& out, std::vector<LinePath>& paths,
                                  std::vector<std::array<int, 2>>& feature_edges, const SurfaceLocator& locator,
                                  const SizeField& size);

/// Where two lines pass closer than kCloseGap x the size without meeting (intersection circles
/// of a sphere cluster 0.0003 apart), the strip between them holds only slivers. Two points of
/// the lines joined by a face edge merge as beside a wedge tip; a point facing the middle part
/// of the other line's segment (a cap) joins that line instead: the segment flips to the edge
/// from it to the point across, and the line runs through it (where it is, or halfway to the
/// segment or on it, the first of these that raises the smallest angle). Either only where a
/// face around is under `below_rad` and the change raises the smallest angle there, the link
/// condition holds and no face turns by more than acos(0.7). Once the lines meet, the wedges on
/// either side are relax_wedge_tips' to take. Returns the points merged into or snapped.
std::vector<int> close_line_gaps(OutputMesh& out, std::vector<LinePath>& paths,
                                 std::vector<std::array<int, 2>>& feature_edges, const SurfaceLocator& locator,
                                 const SizeField& size, double below_rad);

}  // namespace mr::remesh
