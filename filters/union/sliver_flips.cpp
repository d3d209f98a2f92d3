// Edge flips of the sliver step: Lawson's flips of the input's flat slivers, which move
// nothing, and the checked flips of the cut's faces.
#include "union/sliver_collapser.h"

#include <vector>

namespace mr::surface_union::slivers {

bool Collapser::below_threshold(int f, double tan_threshold) const {
  // The smallest angle lies opposite the shortest side.
  const auto& t = r_.faces[f];
  int z = 0;
  double shortest = HUGE_VAL;
  for (int k = 0; k < 3; ++k) {
    const V3 e = sub3(P(t[(k + 1) % 3]), P(t[k]));
    if (dot(e, e) < shortest) {
      shortest = dot(e, e);
      z = k;
    }
  }
  const V3 o = P(t[(z + 2) % 3]);
  const V3 a = sub3(P(t[z]), o), b = sub3(P(t[(z + 1) % 3]), o);
  return norm(cross(a, b)) < tan_threshold * dot(a, b);
}

int Collapser::flat_flip(int f, int z) {
  const int u = r_.faces[f][z], v = r_.faces[f][(z + 1) % 3], c = r_.faces[f][(z + 2) % 3];
  if (cut_[f] || line_.count(ekey(u, v))) return -1;
  const int g = face_across(f, u, v);
  if (g < 0 || cut_[g]) return -1;
  const double before = std::min(min_angle(f), min_angle(g));
  if (!(before < threshold_)) return -1;  // the input's good faces keep their shape
  const int d = third_corner(g, u, v);
  const V3 n_f = cross(sub3(P(v), P(u)), sub3(P(c), P(u)));
  const V3 n_g = cross(sub3(P(u), P(v)), sub3(P(d), P(v)));
  if (!(dot(n_f, n_g) > 0) || norm(cross(n_f, n_g)) > kFlatSine * norm(n_f) * norm(n_g)) return -1;
  {  // Locally Delaunay already (the angles at c and d sum to at most pi): no flip raises
     // the smallest angle. Cheaper than the angles, which decide the rest.
    const V3 cu = sub3(P(u), P(c)), cv = sub3(P(v), P(c)), du = sub3(P(u), P(d)), dv = sub3(P(v), P(d));
    if (norm(cross(cu, cv)) * dot(du, dv) + dot(cu, cv) * norm(cross(du, dv)) >= 0) return -1;
  }
  const double after = std::min(smallest_angle(P(u), P(d), P(c)), smallest_angle(P(d), P(v), P(c)));
  if (!(after > before + kFlatFlipGain) || !flat_convex_quad(P(u), P(v), P(c), P(d)) || edge_exists(c, d)) return -1;
  if (!in_slab(f) || !in_slab(g)) {  // (the new faces lie within the two old ones)
    for (int h : {f, g}) for (int y : r_.faces[h]) defer(y);
    return -1;
  }
  // (Both stay the input's faces, on the cut's surface: not treated by the other moves.)
  const bool f_worse = min_angle(f) <= min_angle(g);
  flip(f, g, u, v, c, d);
  // Both new faces lie across both old ones; their source is the worse one's, so that the
  // input face a face is measured against had no better angle (slivers_left.h): the flip
  // raised the pair's smallest angle above it.
  if (!r_.face_source.empty()) {
    const int worse = r_.face_source[size_t(f_worse ? f : g)];
    r_.face_source[size_t(f)] = r_.face_source[size_t(g)] = worse;
  }
  refile(f);
  refile(g);
  for (int x : {u, v, c, d}) mark_around(x);
  return g;
}

int Collapser::flip_flat_slivers(const std::vector<char>* seed) {
  const double tan_threshold = std::tan(threshold_);
  std::vector<std::pair<int, int>> stack;  // (face, side), face order from the top
  for (int f = int(r_.faces.size()) - 1; f >= 0; --f) {
    if (!alive_[f] || cut_[f]) continue;
    const auto& t = r_.faces[f];
    if (seed && !(*seed)[t[0]] && !(*seed)[t[1]] && !(*seed)[t[2]]) continue;
    if (below_threshold(f, tan_threshold))
      for (int z = 2; z >= 0; --z) stack.push_back({f, z});
  }
  int flips = 0;
  // Each flip raises the mesh's sorted angles, so this ends; the cap guards rounding.
  const long cap = 50L * long(r_.faces.size()) + 1000;
  for (long steps = 0; !stack.empty() && steps < cap; ++steps) {
    const auto [f, z] = stack.back();
    stack.pop_back();
    const int g = flat_flip(f, z);
    if (g < 0) continue;
    ++flips;
    // f = (u, d, c) and g = (d, v, c): the quad's outer sides are f's 0 and 2, g's 0 and 1.
    stack.push_back({g, 1});
    stack.push_back({g, 0});
    stack.push_back({f, 2});
    stack.push_back({f, 0});
  }
  return flips;
}

bool Collapser::attempt_flip(int f, int z) {
  const int u = r_.faces[f][z], v = r_.faces[f][(z + 1) % 3], c = r_.faces[f][(z + 2) % 3];
  if (line_.count(ekey(u, v)) ) return false;
  const int g = face_across(f, u, v);
  if (g < 0) return false;
  if (!in_slab(f) || !in_slab(g)) {  // (the new faces lie within the two old ones)
    for (int h : {f, g}) for (int y : r_.faces[h]) defer(y);
    return false;
  }
  const int d = third_corner(g, u, v);
  if (edge_exists(c, d)) return false;  // the new edge must not exist already
  const V3 n_f = cross(sub3(P(v), P(u)), sub3(P(c), P(u)));
  const V3 n_g = cross(sub3(P(u), P(v)), sub3(P(d), P(v)));
  const V3 n1 = cross(sub3(P(d), P(u)), sub3(P(c), P(u)));
  const V3 n2 = cross(sub3(P(v), P(d)), sub3(P(c), P(d)));
  for (const V3& n : {n1, n2})
    if (!(norm(n) > 0) || dot(n, n_f) <= 0 || dot(n, n_g) <= 0) return false;
  // How far the surface moves: the distance between the old and the new diagonal.
  const V3 cross_diagonals = cross(sub3(P(v), P(u)), sub3(P(d), P(c)));
  const double lc = norm(cross_diagonals);
  if (!(lc > 0) || std::fabs(dot(sub3(P(c), P(u)), cross(sub3(P(v), P(u)), sub3(P(d), P(u))))) / lc > max_dev_) return false;
  const double before = std::min(min_angle(f), min_angle(g));
  const double after = std::min(smallest_angle(P(u), P(d), P(c)), smallest_angle(P(d), P(v), P(c)));
  if (!(after > before)) return false;
  // (The diagonals' distance bounds the move only where they pass over each other: the
  // two pairs of faces are compared as well, in stays_near.)
  // Six times the volume change, relative to u for accuracy.
  auto rel = [&](int x) { return sub3(P(x), P(u)); };
  const double dv6 = det(rel(u), rel(d), rel(c)) + det(rel(d), rel(v), rel(c)) - det(rel(u), rel(v), rel(c)) -
                     det(rel(v), rel(u), rel(d));
  // Not affordable: some vertex must be able to give the volume back after the flip,
  // planned on the flipped faces (no crossing check) before the flip's own check. 280
  // of box.STL's 1055 flips were checked, applied and undone for want of one.
  size_t first_compensator = 0;
  if (dv6 != 0 && std::fabs(dv6) / 6 > volume_budget_) {
    const FlipUndo undo = flip(f, g, u, v, c, d);
    flip_compensators(u, v, c, d, scratch_compensators_);
    V3 at;
    while (first_compensator < scratch_compensators_.size() &&
           !plan_compensation(scratch_compensators_[first_compensator], dv6, at))
      ++first_compensator;
    unflip(f, g, u, v, c, d, undo);
    if (first_compensator == scratch_compensators_.size()) return false;
  }
  start_move();
  replaced_ = {f, g};
  new_ids_ = {{u, d, c}, {d, v, c}};
  new_pos_ = {{P(u), P(d), P(c)}, {P(d), P(v), P(c)}};
  // A flat convex quad (CAD plates) covers the same place after the flip: nothing to check.
  if (!flat_convex_quad(P(u), P(v), P(c), P(d))) {
    if (replaces_touching_face() || folds_more() || !near_and_clear(1e300, true)) return false;
    keep_cut_distance();
  }
  const FlipUndo undo = flip(f, g, u, v, c, d);
  // Filed at their new corners before a compensating move's crossing check looks for the
  // faces near it: filed at the old ones, a flipped face was missed where its box grew, and
  // a ring vertex moved into it (fuzz_union.py --models --transform --params seed 4528).
  grid_.add(f);
  grid_.add(g);
  // Give the volume back by a small move of one free vertex (from the first the plan
  // found: those before it cannot); else it is paid from the budget.
  bool compensated = dv6 == 0;
  if (!compensated) {
    flip_compensators(u, v, c, d, scratch_compensators_);
    for (size_t n = first_compensator; n < scratch_compensators_.size() && !compensated; ++n)
      compensated = compensate(scratch_compensators_[n], dv6);
  }
  if (!compensated) {
    if (std::fabs(dv6) / 6 > volume_budget_) {
      unflip(f, g, u, v, c, d, undo);
      grid_.add(f);
      grid_.add(g);
      return false;
    }
    volume_budget_ -= std::fabs(dv6) / 6;
  }
  refile(f);
  refile(g);
  cut_[f] = cut_[g] = cut_[f] || cut_[g];  // both new faces replace a cut face: treated on
  for (int x : {u, v, c, d}) mark_around(x);
  return true;
}

}  // namespace mr::surface_union::slivers
