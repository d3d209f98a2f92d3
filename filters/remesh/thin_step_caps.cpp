#include "remesh/thin_step_caps.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace mr::remesh {

namespace {

// Steps lower than this x target are thin; caps never go below kFloor x target.
constexpr double kThin = 0.1, kFloor = 0.05;
// Rims and slots narrower than this x target are capped: 1.7 x their width is then under the
// target, and a layer of target-sized faces across them is under 30 degrees.
constexpr double kNarrowRim = 0.55;
// A rim or slot: the faces beyond its two lines turned from each other by more than 90 degrees
// (a plate's edge, 180; the narrow facet between the flat side and the curved side of
// rabbit.obj's ears, 144). Strips between faces turned less (chamfers, ledges) are left to the
// thin-step rules.
constexpr double kRimCos = 0.0;
// Points on the two lines right across from each other (the front's usual layout) make right
// triangles with legs of the height and the spacing: 1.7 x the height gives 30.5 degrees.
constexpr double kCap = 1.7;
// The two lines must run beside each other along at least this x target: a shorter step (a
// face or two where lines crowd at a corner) is meshed as well without caps, and caps there
// grade the crowd's faces worse (fuzz_union --models, exact unions at 1%: seed 1 30.3 -> 19.0,
// seed 13 24.6 -> 9.8 degrees).
constexpr double kMinRun = 1.0;
// Faces beyond the two lines facing the same way: within 30 degrees.
constexpr double kCosAligned = 0.866;
// A seam: the faces on both sides of a line in one plane (within a degree). Not within 30: at a
// ridge angle of 20 degrees, noise makes such ridges by the thousand (the bunny with 1% noise
// regridded at 2% was left with 120 open sides).
constexpr double kCosSeam = 0.99985;

enum class Strip { kStep, kRim };

int cap_strips(const Surface& s, const std::vector<std::array<bool, 3>>& ridge, double target, Strip kind,
               std::vector<double>& cap) {
  const int nf = int(s.faces.size());
  // Per vertex, the ridge sides of faces there: (the side's other end, the face). A ridge edge
  // is listed once from each face along it.
  std::vector<std::vector<std::array<int, 2>>> ridges_at(s.points.size());
  for (int f = 0; f < nf; ++f)
    for (int z = 0; z < 3; ++z)
      if (ridge[size_t(f)][size_t(z)]) {
        const int u = s.faces[size_t(f)][size_t(z)], w = s.faces[size_t(f)][size_t((z + 1) % 3)];
        ridges_at[size_t(u)].push_back({w, f});
        ridges_at[size_t(w)].push_back({u, f});
      }
  // The line through the apex runs beside the side (a to b): one of its ridge edges there runs
  // along the side (within 30 degrees) for at least kMinRun x target of the side's length (a
  // line that leaves the apex away from the side, as at the reflex corner of an L-shaped end
  // face cut into a sliver, is no step), and none of those ends nearer than half the height to
  // the side's line (two lines closing in on each other make a wedge, whose narrow end no size
  // fits).
  auto runs_beside = [&](int apex, const Point3& a, const Point3& b, double height) {
    const double side = (b - a).Norm();
    const Point3 dir = (b - a) / side;
    const Point3& q = s.points[size_t(apex)];
    const double t_apex = (q - a).dot(dir);
    bool runs = false;
    for (const auto& [other, face] : ridges_at[size_t(apex)]) {
      const Point3& p = s.points[size_t(other)];
      const Point3 d = p - q;
      if (!(d.Norm() > 0) || std::fabs(d.dot(dir)) < kCosAligned * d.Norm()) continue;
      const double t = (p - a).dot(dir);
      if (((p - a) - dir * t).Norm() < 0.5 * height) return false;
      runs |= std::min(std::max(t, t_apex), side) - std::max(std::min(t, t_apex), 0.0) >= kMinRun * target;
    }
    return runs;
  };
  // Height of face f over its side z if that side and the apex make a thin step, else -1.
  auto step_height = [&](int f, int z) {
    const auto& t = s.faces[size_t(f)];
    const int beyond = s.neighbour[size_t(f)][size_t(z)];
    const int apex = t[size_t((z + 2) % 3)];
    if (!ridge[size_t(f)][size_t(z)] || beyond < 0 || ridges_at[size_t(apex)].empty()) return -1.0;
    const Point3 &a = s.points[size_t(t[size_t(z)])], &b = s.points[size_t(t[size_t((z + 1) % 3)])];
    const double side = (b - a).Norm();
    const double height = side > 0 ? ((b - a) ^ (s.points[size_t(apex)] - a)).Norm() / side : 0.0;
    if (!(height > 0 && height < (kind == Strip::kStep ? kThin : kNarrowRim) * target)) return -1.0;
    // Beyond the ridge at the apex (a face of another patch), the surface must go on as beyond
    // this side: a ledge (both beyond faces facing the same way, this face turned from them), or
    // a strip between a crease and a seam in a flat side, the seam on either line (as where two
    // united bodies' coplanar sides meet). A rim or a slot (the surfaces beyond face apart) and a
    // chamfer (turned less than a ledge) are neither. (Degenerate faces have no normal: never.)
    const Point3 &n = s.face_normal[size_t(f)], &nb = s.face_normal[size_t(beyond)];
    auto flat = [&](const Point3& m) { return m * n > kCosSeam; };
    bool step = false;
    for (const auto& [other, g] : ridges_at[size_t(apex)]) {
      if (g == beyond || s.group[size_t(g)] == s.group[size_t(f)]) continue;
      const Point3& ng = s.face_normal[size_t(g)];
      if (kind == Strip::kRim) step = ng * nb < kRimCos;
      else step = (ng * nb > kCosAligned && !flat(nb)) || (flat(ng) != flat(nb));
      if (step) break;
    }
    return step && runs_beside(apex, a, b, height) ? height : -1.0;
  };
  int capped = 0;
  for (int f = 0; f < nf; ++f) {
    double height = -1;
    for (int z = 0; z < 3 && height < 0; ++z) height = step_height(f, z);
    if (height < 0) continue;
    const double h = std::max(kCap * height, kFloor * target);
    for (int v : s.faces[size_t(f)]) {
      double& c = cap[size_t(v)];
      c = c > 0 ? std::min(c, h) : h;
    }
    ++capped;
  }
  return capped;
}

}  // namespace

int cap_thin_steps(const Surface& s, const std::vector<std::array<bool, 3>>& ridge, double target,
                   std::vector<double>& cap) {
  return cap_strips(s, ridge, target, Strip::kStep, cap);
}

int cap_narrow_rims(const Surface& s, const std::vector<std::array<bool, 3>>& ridge, double target,
                    std::vector<double>& cap) {
  return cap_strips(s, ridge, target, Strip::kRim, cap);
}

namespace {

// Faces a size field asks for on input face f: the integral of 1 / (equilateral area of size h)
// over the face, by the midpoint rule on kCuts x kCuts sub-triangles (the size is linear on the
// face; a cap at one corner of a long CAD face falls off within a few sub-triangles, where
// samples at the corners and side midpoints weighed the cap over a seventh of the face: on
// joint.off united with two copies at 1% they counted 37,000 faces more where the regrid made
// 8,000 more, and this rule counts 6,000).
constexpr int kCuts = 6;
double expected_faces_on(const Surface& s, const SizeField& size, int f) {
  const auto& t = s.faces[size_t(f)];
  const double area = 0.5 * ((s.points[t[1]] - s.points[t[0]]) ^ (s.points[t[2]] - s.points[t[0]])).Norm();
  double sum = 0;
  int count = 0;
  for (int i = 0; i < kCuts; ++i)
    for (int j = 0; i + j < kCuts; ++j)
      for (int up = 0; up < (i + j + 1 < kCuts ? 2 : 1); ++up) {
        // Centroid of the sub-triangle (upright or inverted) at grid cell (i, j).
        const double a = (3 * i + (up ? 2 : 1)) / (3.0 * kCuts), b = (3 * j + (up ? 2 : 1)) / (3.0 * kCuts);
        const double h = std::max(size.at(f, {1 - a - b, a, b}), 1e-300);
        sum += 1.0 / (h * h);
        ++count;
      }
  return area * sum / count / (0.25 * std::sqrt(3.0));
}

// The caps may add at most this share of the faces the field asks for without them (see the
// header).
constexpr double kThinStepBudget = 0.5;

/// The faces `with` asks for beyond `base` (which differ only where `with` lowered a corner's
/// size), and all the faces `base` asks for.
std::pair<double, double> faces_before_and_added(const Surface& surface, const SizeField& base, const SizeField& with) {
  double before = 0, added = 0;
  for (int f = 0; f < int(surface.faces.size()); ++f) {
    const double faces = expected_faces_on(surface, base, f);
    before += faces;
    const auto& t = surface.faces[size_t(f)];
    if (with.at_vertex(t[0]) < base.at_vertex(t[0]) || with.at_vertex(t[1]) < base.at_vertex(t[1]) ||
        with.at_vertex(t[2]) < base.at_vertex(t[2]))
      added += expected_faces_on(surface, with, f) - faces;
  }
  return {before, added};
}

/// `field` refined by the caps `add` writes into a copy of `kept`'s, when that asks for at most
/// kThinStepBudget x the faces `field` asks for more; then `kept` takes those caps. Returns the
/// number of places `add` capped when they were taken, else 0.
template <class AddCaps>
int refine_within_budget(const Surface& surface, SizeParams& kept, std::optional<SizeField>& field, AddCaps add) {
  SizeParams refined = kept;
  refined.vertex_cap.resize(surface.points.size(), 0.0);
  const int count = add(refined.vertex_cap);
  if (count == 0) return 0;
  SizeField with(surface, refined);
  const auto [before, added] = faces_before_and_added(surface, *field, with);
  if (added > kThinStepBudget * before) return 0;
  field.emplace(std::move(with));
  kept = std::move(refined);
  return count;
}

}  // namespace

SizeField size_field_with_steps_and_necks(const Surface& surface, const std::vector<std::array<bool, 3>>& ridge,
                                     const SizeParams& sp, double target, int* thin_step_faces,
                                     const std::vector<double>* neck_cap, int* neck_points,
                                     int* narrow_rim_faces) {
  SizeParams kept = sp;
  std::optional<SizeField> field;
  field.emplace(surface, sp);
  // Each kind of cap on top of those taken before, within a budget of its own: over it, the
  // field stays as it was.
  const int steps = refine_within_budget(surface, kept, field, [&](std::vector<double>& cap) {
    return cap_thin_steps(surface, ridge, target, cap);
  });
  const int rims = refine_within_budget(surface, kept, field, [&](std::vector<double>& cap) {
    return cap_narrow_rims(surface, ridge, target, cap);
  });
  const int necks = !neck_cap ? 0 : refine_within_budget(surface, kept, field, [&](std::vector<double>& cap) {
    int count = 0;
    for (size_t v = 0; v < neck_cap->size() && v < cap.size(); ++v) {
      const double c = (*neck_cap)[v];
      if (!(c > 0)) continue;
      cap[v] = cap[v] > 0 ? std::min(cap[v], c) : c;
      ++count;
    }
    return count;
  });
  if (thin_step_faces) *thin_step_faces = steps;
  if (narrow_rim_faces) *narrow_rim_faces = rims;
  if (neck_points) *neck_points = necks;
  return std::move(*field);
}

}  // namespace mr::remesh
