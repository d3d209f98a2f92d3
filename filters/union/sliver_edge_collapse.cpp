// The sliver step's main move: an edge collapsed into one of its ends (or onto a point
// between them that keeps the volume), weighed in a dry run first.
#include "union/sliver_collapser.h"

namespace mr::surface_union::slivers {

bool Collapser::try_collapse(int v, int w, bool apply, double* dv_out, double beat) {
  if (collapse_still_refused(v, w)) return false;
  if (!star_in_slab(v) || !star_in_slab(w)) return false;
  // Every refusal up to the crossing check is remembered (see collapse_still_refused).
  auto refuse = [&] {
    collapse_refused_at_[collapse_key(v, w)] = clock_;
    return false;
  };
  // Lines: v may only slide along its own line edge (v, w) at a vertex of line degree 2, or,
  // where two lines pass closer than a sliver allows (bodies nearly touching on a third one),
  // join a vertex w of the other line: the lines then meet at w. Or bend onto a vertex w
  // of an input crease within the deviation bound: a line running a hair beside a plate's
  // edge (CAD parts that nearly line up, box.STL) leaves a strip that no move inside it
  // can mend. Only at creases: on curved bodies a bent line traps worse slivers later.
  const bool vw_line = line_.count(ekey(v, w)) > 0;
  const bool joins_line = line_degree_[v] == 2 && !vw_line && line_degree_[w] > 0;
  const bool bends_line = line_degree_[v] == 2 && !vw_line && line_degree_[w] == 0 &&
                          norm(sub3(P(v), P(w))) <= max_dev_ && on_crease(w);
  if (line_degree_[v] > 0 && !(vw_line && line_degree_[v] >= 2) && !joins_line && !bends_line) return refuse();
  std::vector<int>& fv = scratch_fv_;
  std::vector<int>& fw = scratch_fw_;
  live_faces(v, fv);
  live_faces(w, fw);
  // Link condition: v and w share exactly the two opposite vertices of their two faces.
  int shared_faces = 0;
  for (int f : fv)
    if (has_corner(r_.faces[f], w)) ++shared_faces;
  if (shared_faces != 2) return refuse();
  std::vector<int>& nv = scratch_nv_;  // one-rings (unique; marked, no sorting)
  std::vector<int>& nw = scratch_nw_;
  nv.clear();
  nw.clear();
  if (ring_mark_.size() != r_.vertices.size()) ring_mark_.assign(r_.vertices.size(), 0);
  const int in_w = ++ring_stamp_, in_v = ++ring_stamp_;
  for (int f : fw)
    for (int x : r_.faces[f])
      if (ring_mark_[x] != in_w) {
        ring_mark_[x] = in_w;
        nw.push_back(x);
      }
  int common = 0;
  for (int f : fv)
    for (int x : r_.faces[f]) {
      if (ring_mark_[x] == in_v) continue;
      if (ring_mark_[x] == in_w && x != v && x != w) ++common;
      ring_mark_[x] = in_v;
      nv.push_back(x);
    }
  if (common != 2) return refuse();
  // Target: w's position, moved along the volume gradient of the new star so that the
  // enclosed volume stays the same (Lindstrom-Turk); the move is tiny where the
  // surface is nearly flat. Coordinates relative to w keep the sums accurate. w stays
  // put when it is on a line other than the one v slides along.
  const bool w_free = line_degree_[w] == 0 || (vw_line && line_degree_[w] == 2);
  const V3 o = P(w);
  auto rel = [&](int x) { return sub3(P(x), o); };
  double s_old = 0;  // six times the old volume of the star (relative to o)
  V3 g{0, 0, 0};     // six times the new volume is g . p (p relative to o)
  for (int pass = 0; pass < 2; ++pass)
    for (int f : pass == 0 ? fv : fw) {
      const auto& t = r_.faces[f];
      const bool has_v = has_corner(t, v);
      const bool has_w = has_corner(t, w);
      if (pass == 1 && has_v) continue;  // counted with v's faces
      s_old += det(rel(t[0]), rel(t[1]), rel(t[2]));
      if (has_v && has_w) continue;  // dies
      for (int z = 0; z < 3; ++z)
        if (t[z] == v || t[z] == w) {
          const V3 bc = cross(rel(t[(z + 1) % 3]), rel(t[(z + 2) % 3]));
          for (int k = 0; k < 3; ++k) g[k] += bc[k];
        }
    }
  const double gg = dot(g, g);
  // The score is |s_old| / 6 whichever target is kept: w's own place changes the volume by
  // -s_old and sweeps none; the volume-keeping target changes none and sweeps |p| sqrt(gg) =
  // |s_old| (up to rounding, hence the margin). A dry run that cannot beat `beat` is not weighed.
  if (!apply && std::fabs(s_old) / 6 * (1 - 1e-12) >= beat) return false;
  // Checks one target p (relative to w): no flipped or degenerate face, bounded
  // deviation, a better worst angle; gives six times the volume change.
  auto acceptable = [&](const V3& p, double& dv) {
    if (norm(p) > max_dev_) return false;
    const bool moves_w = p[0] != 0 || p[1] != 0 || p[2] != 0;
    const V3 target{o[0] + p[0], o[1] + p[1], o[2] + p[2]};
    double before = 1e300, after = 1e300;
    int bad_before = 0, bad_after = 0;
    near_old_.clear();
    near_new_.clear();
    for (int pass = 0; pass < 2; ++pass) {
      if (pass == 1 && !moves_w) break;  // w's other faces keep their shape
      for (int f : pass == 0 ? fv : fw) {
        const auto& t = r_.faces[f];
        const bool has_v = has_corner(t, v);
        const bool has_w = has_corner(t, w);
        if (pass == 1 && has_v) continue;
        const double a0 = min_angle(f);
        if (pass == 0) before = std::min(before, a0);
        bad_before += a0 < threshold_;
        near_old_.push_back({P(t[0]), P(t[1]), P(t[2])});
        if (has_v && has_w) continue;
        V3 q[3];
        for (int z = 0; z < 3; ++z) q[z] = t[z] == v || t[z] == w ? target : P(t[z]);
        near_new_.push_back({q[0], q[1], q[2]});
        const V3 n_old = cross(sub3(P(t[1]), P(t[0])), sub3(P(t[2]), P(t[0])));
        const V3 n_new = cross(sub3(q[1], q[0]), sub3(q[2], q[0]));
        const double ln = norm(n_new), lo = norm(n_old);
        if (!(ln > 0) || dot(n_old, n_new) <= 0.1 * lo * ln) return false;
        if (std::fabs(dot(sub3(P(has_v ? v : w), q[0]), n_new)) / ln > max_dev_) return false;
        const double a = smallest_angle(q[0], q[1], q[2]);
        // A face the cut did not make is not turned into a worse sliver (nothing would
        // treat it), but by a bend, which then hands it to the step (below).
        if (!bends_line && !cut_[f] && a < threshold_ && a < a0) return false;
        after = std::min(after, a);
        bad_after += a < threshold_;
      }
    }
    // Better: a larger worst angle, or fewer slivers without making the worst one
    // much worse (two neighbouring slivers often cannot both improve in one step).
    // Not below a degree, though: repeated halvings would ratchet a needle towards zero.
    if (!(after > before || (bad_after < bad_before && after >= 0.5 * before && after >= kNoRatchetBelow)))
      return false;
    // Every point of the star moves at most as far as v (w is within the bound); where v
    // moves further, the faces may still lie near the old ones (a short edge on a smooth
    // star), or not (a star folded over: a fin of rabbit.obj lost 0.045 of its height).
    if (norm(sub3(target, P(v))) > max_dev_ && !patches_within(near_old_, near_new_, max_dev_)) return false;
    dv = dot(g, p) - s_old;
    return true;
  };
  // First the volume-keeping target; if it is refused (a large move on a strongly
  // curved star), w itself, with the volume given back by a neighbour or the budget.
  V3 p{0, 0, 0};
  double dv = 0;
  // The chosen candidate was just weighed in a dry run, with nothing changed since.
  const Weighed* weighed = nullptr;
  if (apply)
    for (const Weighed& c : weighed_)
      if (c.v == v && c.w == w && c.clock == clock_) weighed = &c;
  if (weighed) {
    p = weighed->p;
    dv = weighed->dv;
  } else {
    bool ok = false;
    if (w_free && gg > 0) {
      for (int k = 0; k < 3; ++k) p[k] = s_old / gg * g[k];
      ok = acceptable(p, dv);
    }
    if (!ok) {
      p = {0, 0, 0};
      if (!acceptable(p, dv)) return refuse();
    }
  }
  const V3 target{o[0] + p[0], o[1] + p[1], o[2] + p[2]};
  const bool moved = p[0] != 0 || p[1] != 0 || p[2] != 0;
  if (std::fabs(dv) / 6 > volume_budget_) return refuse();
  // Score: the volume change plus the volume swept by the compensating move.
  if (dv_out) *dv_out = std::fabs(dv) / 6 + norm(p) * std::sqrt(gg) / 6;
  if (!apply) {
    weighed_[next_weighed_++ % weighed_.size()] = {v, w, clock_, p, dv};
    return true;
  }
  // The new star must not run into the rest of the surface (thin plates, nearly
  // touching bodies): checked exactly before anything changes.
  start_move();
  for (int f : fv) {
    const auto& t = r_.faces[f];
    if (has_corner(t, w)) replaced_.push_back(f);  // dies
    else propose(f, v, w, target);
  }
  if (moved)
    for (int f : fw)
      if (!has_corner(r_.faces[f], v)) propose(f, w, w, target);
  if (!proposed_in_slab()) return false;
  if (!cover_unchanged(v, moved ? w : -1)) {
    if (replaces_touching_face() || folds_more() || !near_and_clear(std::max(norm(sub3(target, P(v))), norm(p)))) return false;
    keep_cut_distance();
  }
  const double budget_before = volume_budget_;
  volume_budget_ -= std::fabs(dv) / 6;
  for (int x : nv) changed_[x] = 1;
  for (int x : nw) changed_[x] = 1;
  if (moved) {
    place(w, target);
    for (int f : fw) {
      refile(f);
      if (bends_line) cut_[f] = 1;  // reshaped by the step: treated like the cut's own faces
    }
  }
  const std::vector<int> link = nv;  // copies: compensate() reuses the scratch vectors
  for (int f : fv) {
    auto& t = r_.faces[f];
    if (has_corner(t, w)) {
      touched(f);
      alive_[f] = 0;
      grid_.remove(f);
      continue;
    }
    for (int& x : t)
      if (x == v) x = w;
    vf_[w].push_back(f);
    refile(f);
    if (bends_line) cut_[f] = 1;  // likewise
  }
  vf_[v].clear();
  // Line edges of v now start at w (v's neighbours are the vertices of its old faces).
  if (line_degree_[v] > 0) {
    std::vector<std::pair<int, int>> moved;
    for (int x : nv) {
      if (x == v) continue;
      auto it = line_.find(ekey(v, x));
      if (it == line_.end()) continue;
      if (x != w) moved.push_back(ekey(x, w));
      --line_degree_[v];
      --line_degree_[x];
      line_.erase(it);
    }
    for (const auto& e : moved)
      if (line_.insert(e).second) { ++line_degree_[e.first]; ++line_degree_[e.second]; }
  }
  // w could not take the compensating move: a free neighbour gives the volume back.
  if (!moved && dv != 0)
    for (int x : link)
      if (x != v && x != w && compensate(x, dv)) {
        volume_budget_ = budget_before;
        break;
      }
  return true;
}

}  // namespace mr::surface_union::slivers
