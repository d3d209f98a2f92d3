// Size caps on thin steps. Where two feature lines run closer than a tenth of the target with
// the surface going on the same way beyond both (a ledge where two united bodies' walls stand
// 0.04 x target apart, or a seam where their coplanar sides meet beside an edge), the faces
// between the lines are as thin as the strip whatever the points along them: 5-degree strips
// at 1% (joint.off united with a shifted copy). Elements about as long as the strip is wide fit
// across it; the caps ask for them there, and the size field's gradation brings the size back
// up around. Lines closing in on each other (wedges, whose narrow end no size fits) and steps
// shorter than an element are left alone. Rims and slots (the surfaces beyond face apart) are
// no steps; cap_narrow_rims caps them, up to a wider strip.
#pragma once

#include "remesh/size_field.h"
#include "remesh/surface_locator.h"

#include <array>
#include <vector>

namespace mr::remesh {

/// Lowers `cap` (per surface point; 0 = no cap) at the corners of thin-step faces of `s`, whose
/// `ridge` (per face and side, stage 1's) are the feature lines: a face with a ridge side, its third corner on another ridge whose line runs beside that side for at least
/// `target` without closing in on it, less than 0.1 x `target` high over the side, and beyond
/// the two ridges either faces within 30 degrees of each other with the face itself turned
/// further from them (a ledge), or on one of them the face's own plane and on the other not (a
/// strip between a crease and a seam in a flat side).
/// The cap is 1.7 x the face's height (aligned points on both lines then make right triangles
/// of 30 degrees), never below 0.05 x `target`. Returns the number of faces that capped.
int cap_thin_steps(const Surface& s, const std::vector<std::array<bool, 3>>& ridge, double target,
                   std::vector<double>& cap);

/// Lowers `cap` like cap_thin_steps at the corners of faces across a narrow rim or slot: two
/// feature lines running beside each other closer than 0.55 x `target`, the faces beyond them
/// turned from each other by more than 90 degrees, as along a thin plate's edge. A layer of
/// target-sized faces across such a strip is under 30 degrees. Returns the faces that capped.
int cap_narrow_rims(const Surface& s, const std::vector<std::array<bool, 3>>& ridge, double target,
                    std::vector<double>& cap);

/// The size field of `sp` on `surface`, with the thin steps' caps where they
/// add at most half the faces the field asks for without them: the exact union's needles are thin
/// steps by the hundred, and meshing them all took 5x the faces and 30x the time (joint.off united
/// with two copies at 1%). `thin_step_faces` (optional) gets the input faces that capped (0: none,
/// or over that budget).
/// The narrow rims' caps (cap_narrow_rims) come on top, within a budget of their own measured
/// against the field with the steps; `narrow_rim_faces` (optional) gets their faces (0: none, or
/// over that budget).
/// `neck_cap` (optional, per surface point, 0 = none; neck_caps.h) is applied on top of those,
/// within a budget of its own: over it the necks are dropped and the steps and rims stay. `neck_points` (optional) gets the points the necks capped (0: none, or
/// over that budget).
SizeField size_field_with_steps_and_necks(const Surface& surface, const std::vector<std::array<bool, 3>>& ridge,
                                     const SizeParams& sp, double target, int* thin_step_faces = nullptr,
                                     const std::vector<double>* neck_cap = nullptr, int* neck_points = nullptr,
                                     int* narrow_rim_faces = nullptr);

}  // namespace mr::remesh
