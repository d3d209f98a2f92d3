// The sliver step's vertex moves: removal with the link filled again, slides along a line,
// relocation within the surface, and the compensating moves that give the volume back.
#include "union/sliver_collapser.h"

#include "union/link_triangulation.h"

namespace mr::surface_union::slivers {

bool Collapser::try_junction_slide(int c) {
  if (line_degree_[c] == 0) return false;
  std::vector<int> ring;  // c's line neighbours at junctions (copied: try_collapse reuses scratch)
  std::vector<int>& fc = scratch_fx_;
  live_faces(c, fc);
  for (int f : fc)
    for (int j : r_.faces[f])
      if (j != c && line_degree_[j] >= 3 && line_.count(ekey(c, j)) &&
          std::find(ring.begin(), ring.end(), j) == ring.end())
        ring.push_back(j);
  for (int j : ring)
    if (try_collapse(j, c)) return true;
  return false;
}

bool Collapser::attempt_removal(int v) {
  const int ld = line_degree_[v];
  if (ld != 0 && ld != 2) return false;
  if (!star_in_slab(v)) return false;  // (the new faces lie within the old star)
  // Scratch members: this runs for every sliver corner, pass after pass.
  std::vector<int>& fv = removal_faces_;
  live_faces(v, fv);
  const int k = int(fv.size());
  if (k < 3 || k > kMaxRemovedValence) return false;
  // The link in order: each face (v, a, b) gives the link side a -> b.
  std::vector<std::array<int, 2>>& sides = removal_sides_;
  sides.clear();
  for (int f : fv) {
    const auto& t = r_.faces[f];
    for (int z = 0; z < 3; ++z)
      if (t[z] == v) sides.push_back({t[(z + 1) % 3], t[(z + 2) % 3]});
  }
  std::vector<int>& ring = removal_ring_;
  ring.assign(1, sides[0][0]);
  for (int step = 0; step < k; ++step) {
    int next = -1;
    for (const auto& sd : sides)
      if (sd[0] == ring.back()) next = next < 0 ? sd[1] : -2;
    if (next < 0) return false;  // not a single closed fan
    if (step + 1 < k) {
      if (std::find(ring.begin(), ring.end(), next) != ring.end()) return false;
      ring.push_back(next);
    } else if (next != ring[0]) {
      return false;
    }
  }
  std::array<int, 2> forced{-1, -1};
  if (ld == 2) {
    int n = 0;
    for (int i = 0; i < k; ++i)
      if (line_.count(ekey(v, ring[i]))) forced[n++] = i;
    if (n != 2 || line_.count(ekey(ring[forced[0]], ring[forced[1]]))) return false;
    // The line's new edge is kept without the link triangulation's test that a diagonal is
    // not an edge already (elsewhere in the surface: it would get four faces).
    const int gap = forced[1] - forced[0];
    if (gap != 1 && gap != k - 1 && edge_exists(ring[forced[0]], ring[forced[1]])) return false;
  }
  // (The link triangulation below is the expensive part of a refusal.)
  if (star_unchanged_since(removal_refused_at_[v], v, fv)) return false;
  auto refuse = [&] {
    removal_refused_at_[v] = clock_;
    return false;
  };
  V3 up{0, 0, 0};
  for (int f : fv) {
    const auto& t = r_.faces[f];
    const V3 n = cross(sub3(P(t[1]), P(t[0])), sub3(P(t[2]), P(t[0])));
    for (int c = 0; c < 3; ++c) up[c] += n[c];
  }
  std::vector<V3>& at = removal_at_;
  at.resize(size_t(k));
  for (int i = 0; i < k; ++i) at[i] = P(ring[i]);
  double before = 1e300;
  bool any_cut = false;
  for (int f : fv) {
    before = std::min(before, min_angle(f));
    any_cut |= cut_[f] != 0;
  }
  std::vector<std::array<int, 3>>& tris = removal_tris_;
  tris.clear();
  double after = 0;
  if (!best_polygon_triangulation(
          at, up, [&](int i, int j) { return !edge_exists(ring[i], ring[j]); }, forced, tris, after, before))
    return refuse();
  if (!any_cut && after < threshold_) return refuse();
  // Each new face faces the way of the star and passes within the deviation bound of v.
  const V3 pv = P(v);
  double dv6 = 0;  // six times the volume change (the old faces span nothing seen from v)
  for (const auto& t : tris) {
    const V3 a = sub3(at[t[0]], pv), b = sub3(at[t[1]], pv), c = sub3(at[t[2]], pv);
    const V3 n = cross(sub3(b, a), sub3(c, a));
    const double ln = norm(n);
    if (!(ln > 0) || dot(n, up) <= 0.1 * ln * norm(up)) return refuse();
    if (std::fabs(dot(a, n)) / ln > max_dev_) return refuse();
    dv6 += det(a, b, c);
  }
  if (std::fabs(dv6) / 6 > volume_budget_) return refuse();
  start_move();
  replaced_ = fv;
  for (const auto& t : tris) {
    new_ids_.push_back({ring[t[0]], ring[t[1]], ring[t[2]]});
    new_pos_.push_back({at[t[0]], at[t[1]], at[t[2]]});
  }
  if (ld == 2) new_line_edge_ = ekey(ring[forced[0]], ring[forced[1]]);
  if (!cover_unchanged(v)) {
    if (replaces_touching_face() || folds_more() || !stays_near()) return refuse();
    if (!near_and_clear(1e300)) return false;
    keep_cut_distance();
  }
  // Each new face's source: the old face at one of its corners that is not an end of the
  // line through v (faces at such a corner lie on its side of the line, the same body's).
  std::vector<int>& sources = removal_sources_;
  sources.clear();
  if (!r_.face_source.empty())
    for (const auto& t : tris) {
      int c = t[0];
      for (int z : t)
        if (z != forced[0] && z != forced[1]) { c = z; break; }
      for (int j = 0; j < k; ++j)
        if (sides[size_t(j)][0] == ring[size_t(c)]) { sources.push_back(r_.face_source[size_t(fv[size_t(j)])]); break; }
    }
  // The first k - 2 faces of the star take the new triangles; the last two go.
  for (int x : ring) {
    auto& list = vf_[x];
    list.erase(std::remove_if(list.begin(), list.end(),
                              [&](int f) { return std::find(fv.begin(), fv.end(), f) != fv.end(); }),
               list.end());
  }
  vf_[v].clear();
  for (int i = 0; i < k; ++i) {
    const int f = fv[i];
    if (i < k - 2) {
      r_.faces[f] = new_ids_[size_t(i)];
      if (!sources.empty()) r_.face_source[size_t(f)] = sources[size_t(i)];
      cut_[f] = any_cut;
      for (int x : r_.faces[f]) vf_[x].push_back(f);
      refile(f);
    } else {
      touched(f);
      alive_[f] = 0;
      grid_.remove(f);
    }
  }
  if (ld == 2) {
    const int a = ring[forced[0]], b = ring[forced[1]];
    line_.erase(ekey(v, a));
    line_.erase(ekey(v, b));
    line_degree_[v] = 0;
    line_.insert(ekey(a, b));  // the line's other edges at a and b stay: degrees unchanged
  }
  for (int x : ring) mark_around(x);
  const double budget_before = volume_budget_;
  volume_budget_ -= std::fabs(dv6) / 6;
  if (dv6 != 0)
    for (int x : ring)
      if (compensate(x, dv6)) {
        volume_budget_ = budget_before;
        break;
      }
  return true;
}

bool Collapser::attempt_slide_on_line(int x) {
  if (line_degree_[x] != 2 || !star_in_slab(x)) return false;
  std::vector<int>& fx = slide_faces_;  // (scratch: tried for every line vertex, pass after pass)
  live_faces(x, fx);
  if (star_unchanged_since(slide_refused_at_[x], x, fx)) return false;
  // Every refusal up to the crossing check is remembered (see star_unchanged_since).
  auto refuse = [&] {
    slide_refused_at_[x] = clock_;
    return false;
  };
  int ends[2], n = 0;
  for (int f : fx)
    for (int y : r_.faces[f])
      if (y != x && n < 2 && line_.count(ekey(x, y)) && (n == 0 || ends[0] != y)) ends[n++] = y;
  if (n != 2) return refuse();
  double before = 1e300;
  for (int f : fx) before = std::min(before, min_angle(f));
  const V3 o = P(x);
  V3 best_at = o;
  double best = before;
  for (int e = 0; e < 2; ++e) {
    const V3 d = sub3(P(ends[e]), o);
    for (double t : {0.15, 0.3, 0.5, 0.7}) {
      const V3 at{o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
      // The line now runs straight from the other neighbour to `at`: it leaves the
      // intersection curve by at most the distance of x from that chord.
      const V3 chord = sub3(at, P(ends[1 - e]));
      const V3 off = cross(sub3(o, P(ends[1 - e])), chord);
      if (!(norm(chord) > 0) || norm(off) / norm(chord) > max_dev_) continue;
      double worst = 1e300;
      bool fine = true;
      for (int f : fx) {
        V3 q[3];
        if (!moved_face(f, x, at, q)) { fine = false; break; }
        const double a = smallest_angle(q[0], q[1], q[2]);
        // A face no better than the best place so far: this place cannot win.
        if ((!cut_[f] && a < threshold_ && a < min_angle(f)) || !(a > best)) { fine = false; break; }
        worst = std::min(worst, a);
      }
      if (fine && worst > best) { best = worst; best_at = at; }
    }
  }
  if (!(best > before * (1 + kMinSlideGain))) return refuse();
  // Six times the volume change of the move, given back by a free neighbour or paid.
  double dv6 = 0;
  for (int f : fx) {
    const auto& t = r_.faces[f];
    V3 q[3];
    for (int z = 0; z < 3; ++z) q[z] = t[z] == x ? best_at : P(t[z]);
    dv6 += det(sub3(q[0], o), sub3(q[1], o), sub3(q[2], o));  // old faces span nothing seen from o
  }
  std::vector<int>& ring = slide_ring_;  // free neighbours, which may give the volume back
  ring.clear();
  for (int f : fx)
    for (int y : r_.faces[f])
      if (y != x && line_degree_[y] == 0 && std::find(ring.begin(), ring.end(), y) == ring.end()) ring.push_back(y);
  const bool affordable = std::fabs(dv6) / 6 <= volume_budget_;
  if (!affordable) {
    // Some free neighbour must be able to give the volume back after the move: planned
    // with x moved (no crossing check yet), before anything is checked exactly.
    place(x, best_at);
    bool plan = false;
    V3 at;
    for (int y : ring)
      if (!plan) plan = plan_compensation(y, dv6, at);
    place(x, o);
    if (!plan) return refuse();
  }
  std::vector<std::pair<int, char>>& marks = slide_marks_;  // changed_ before the move, restored if undone
  marks.clear();
  for (int f : fx)
    for (int y : r_.faces[f]) marks.push_back({y, changed_[y]});
  if (!move_vertex(x, fx, best_at)) return false;
  if (dv6 == 0) return true;
  for (int y : ring)
    if (compensate(y, dv6)) return true;
  if (affordable) {
    volume_budget_ -= std::fabs(dv6) / 6;
    return true;
  }
  // Neither given back nor affordable: x goes back where it was (which was clear), and
  // nothing counts as changed.
  place(x, o);
  for (int f : fx) refile(f);
  for (auto it = marks.rbegin(); it != marks.rend(); ++it) changed_[it->first] = it->second;
  return false;
}

bool Collapser::attempt_relocation(int x) {
  if (line_degree_[x] > 0 || !star_in_slab(x)) return false;
  std::vector<int>& fx = scratch_fx_;
  live_faces(x, fx);
  if (fx.empty()) return false;
  const V3 o = P(x);
  V3 g{0, 0, 0}, centroid{0, 0, 0};
  for (int f : fx) {
    const auto& t = r_.faces[f];
    for (int z = 0; z < 3; ++z)
      if (t[z] == x) {
        const V3 b = sub3(P(t[(z + 1) % 3]), o), c = sub3(P(t[(z + 2) % 3]), o);
        const V3 bc = cross(b, c);
        for (int k = 0; k < 3; ++k) {
          g[k] += bc[k];
          centroid[k] += (b[k] + c[k]) / (2.0 * double(fx.size()));
        }
      }
  }
  const double gg = dot(g, g);
  if (!(gg > 0)) return false;
  // Only on a smooth patch (no crease through x): there the slide barely moves the surface.
  for (int f : fx) {
    const auto& t = r_.faces[f];
    const V3 n = cross(sub3(P(t[1]), P(t[0])), sub3(P(t[2]), P(t[0])));
    if (dot(n, g) < kSmoothStarCos * norm(n) * std::sqrt(gg)) return false;
  }
  V3 delta = centroid;
  const double along = dot(g, delta) / gg;
  for (int k = 0; k < 3; ++k) delta[k] -= along * g[k];  // g . delta = 0: same volume
  const double len = norm(delta);
  if (!(len > 0)) return false;
  if (len > max_dev_)
    for (double& d : delta) d *= max_dev_ / len;
  const V3 moved{o[0] + delta[0], o[1] + delta[1], o[2] + delta[2]};
  double before = 1e300, after = 1e300;
  for (int f : fx) {
    V3 q[3];
    if (!moved_face(f, x, moved, q)) return false;
    const double a = smallest_angle(q[0], q[1], q[2]);
    if (!cut_[f] && a < threshold_ && a < min_angle(f)) return false;
    before = std::min(before, min_angle(f));
    after = std::min(after, a);
  }
  if (!(after > before)) return false;
  return move_vertex(x, fx, moved);
}

bool Collapser::move_vertex(int x, const std::vector<int>& fx, const V3& at) {
  start_move();
  for (int f : fx) propose(f, x, x, at);
  if (!proposed_in_slab()) return false;
  // Every point of the faces moves at most as far as x (a slide along a line may move
  // further than the bound: then the patches are compared, unless they cover the same).
  if (!cover_unchanged(x)) {
    const double moved = norm(sub3(at, P(x)));
    if (replaces_touching_face() || folds_more() || !near_and_clear(moved, true, moved)) return false;
    keep_cut_distance();
  }
  place(x, at);
  for (int f : fx) {
    refile(f);
    for (int y : r_.faces[f]) changed_[y] = 1;
  }
  return true;
}

bool Collapser::plan_compensation(int x, double dv6, V3& moved) {
  if (line_degree_[x] > 0 || !star_in_slab(x)) return false;
  std::vector<int>& fx = scratch_fx_;
  live_faces(x, fx);
  const V3 o = P(x);
  V3 g{0, 0, 0};  // six times the volume change is g . delta
  for (int f : fx) {
    const auto& t = r_.faces[f];
    for (int z = 0; z < 3; ++z)
      if (t[z] == x) {
        const V3 bc = cross(sub3(P(t[(z + 1) % 3]), o), sub3(P(t[(z + 2) % 3]), o));
        for (int k = 0; k < 3; ++k) g[k] += bc[k];
      }
  }
  const double gg = dot(g, g);
  if (!(gg > 0)) return false;
  V3 delta;
  for (int k = 0; k < 3; ++k) delta[k] = -dv6 / gg * g[k];
  if (norm(delta) > max_dev_) return false;
  moved = {o[0] + delta[0], o[1] + delta[1], o[2] + delta[2]};
  for (int f : fx) {
    V3 q[3];
    if (!moved_face(f, x, moved, q)) return false;
    if (smallest_angle(q[0], q[1], q[2]) < std::min(min_angle(f), threshold_)) return false;
  }
  return true;
}

bool Collapser::compensate(int x, double dv6) {
  V3 moved;
  return plan_compensation(x, dv6, moved) && move_vertex(x, scratch_fx_, moved);
}

}  // namespace mr::surface_union::slivers
