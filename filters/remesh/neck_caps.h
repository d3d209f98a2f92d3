// Size caps at necks between feature lines. Where two lines that do not meet pass closer than a
// 0.15 x the target (two intersection circles of a sphere cluster nearly touching: the patch
// between them narrows to a neck 0.06 x target wide), the faces across the neck are as thin as
// the neck whatever the points along the lines: 9-degree faces at 1% on a cluster of 50
// spheres. Points on both lines about as far apart as the neck is wide fit across it; the caps
// ask for them there, and the size field's gradation brings the size back up around. Lines that
// end at one corner (a wedge between them, whose narrow end no size fits, or twin lines) and
// lines that touch in passing, at one or two points (noise), are left alone. Between two lines
// the caller gave (the union's intersection lines) the caps reach wider necks, 0.45 x target.
#pragma once

#include "features/feature_lines.h"
#include "remesh/surface_locator.h"

#include <vector>

namespace mr::remesh {

/// Per line of `lines` (found on `mesh`): 1 where every edge of it is a face edge selected in
/// `mesh` (a line the caller gave, such as the union's intersection lines), else 0; all 0 unless
/// `use_selected`.
std::vector<char> given_lines(const TriMesh& mesh, const std::vector<features::DiscreteLine>& lines, bool use_selected);

/// Lowers `cap` (per surface point; 0 = no cap) at the points of `lines` that lie closer than
/// 0.15 x `target` to another line, not counting lines that end at a corner their own line ends
/// at too, and only in runs of at least three such points in a row along the line. The cap
/// is 1.7 x that distance, never below 0.05 x `target`. Between two lines that are both `given`
/// (per line, as given_lines; missing entries are 0) the reach is 0.45 x `target`, in runs of at
/// least five points, and the floor 0.01 x `target`. Returns the number of points capped.
int cap_necks(const Surface& s, const std::vector<features::DiscreteLine>& lines, const std::vector<char>& given,
              double target, std::vector<double>& cap);

}  // namespace mr::remesh
