#include "union/sliver_collapse.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "common/parallel_for.h"
#include "union/sliver_collapser.h"

namespace mr::surface_union {

namespace {
using slivers::Collapser;
using slivers::CutSurface;
using slivers::Limits;
using slivers::Slab;
using slivers::faces_near_cut;
using slivers::kPi;
}  // namespace

double min_angle_deg(const std::vector<std::array<double, 3>>& v, const std::vector<std::array<int, 3>>& f) {
  double best = 180;
  for (const auto& t : f) best = std::min(best, smallest_angle(v[t[0]], v[t[1]], v[t[2]]) * 180 / kPi);
  return best;
}

namespace {

// Below this many slivers one collapser treats the whole surface: the parts' setup and
// the run along their border would cost more than the second thread saves.
constexpr size_t kMinSliversForParts = 4000;

Limits limits_of(const Result& r, double max_deviation, double max_volume_change) {
  // About a vertex of the surface, not the origin (far from it the terms cancel to noise).
  double volume = 0;
  const V3 o = r.faces.empty() ? V3{0, 0, 0} : r.vertices[size_t(r.faces[0][0])];
  for (const auto& t : r.faces)
    volume += dot(sub3(r.vertices[t[0]], o), cross(sub3(r.vertices[t[1]], o), sub3(r.vertices[t[2]], o))) / 6;
  V3 lo = r.vertices.empty() ? V3{0, 0, 0} : r.vertices[0], hi = lo;
  for (const auto& p : r.vertices)
    for (int k = 0; k < 3; ++k) { lo[k] = std::min(lo[k], p[k]); hi[k] = std::max(hi[k], p[k]); }
  return {max_deviation * norm(sub3(hi, lo)), max_volume_change * std::fabs(volume), std::fabs(volume)};
}

/// A slab's faces and every face reaching into it, with the vertices they use, and
/// what its collapser left.
struct Part {
  Slab slab;
  Result r;
  std::vector<char> cut;
  std::vector<int> face_of, vertex_of;  // local index -> the whole surface's
  std::vector<char> alive, deferred;
  std::vector<double> cut_distance;
  double budget_left = 0;
  int moves = 0, flat_flips = 0;
};

bool reaches_into(const Result& r, int f, const Slab& s) {
  double mn = HUGE_VAL, mx = -HUGE_VAL;
  for (int x : r.faces[f]) {
    mn = std::min(mn, r.vertices[x][s.axis]);
    mx = std::max(mx, r.vertices[x][s.axis]);
  }
  return mn < s.hi && mx > s.lo;
}

void extract(const Result& r, const std::vector<char>& cut, Part& p) {
  std::vector<int> local(r.vertices.size(), -1);
  for (int f = 0; f < int(r.faces.size()); ++f) {
    if (!reaches_into(r, f, p.slab)) continue;
    std::array<int, 3> t;
    for (int z = 0; z < 3; ++z) {
      int& l = local[r.faces[f][z]];
      if (l < 0) {
        l = int(p.vertex_of.size());
        p.vertex_of.push_back(r.faces[f][z]);
        p.r.vertices.push_back(r.vertices[r.faces[f][z]]);
      }
      t[z] = l;
    }
    p.face_of.push_back(f);
    p.r.faces.push_back(t);
    p.r.line_edge.push_back(r.line_edge[f]);
    if (!r.face_source.empty()) p.r.face_source.push_back(r.face_source[f]);
    p.cut.push_back(cut[f]);
  }
}

/// Runs a collapser in part p's slab. `seed` (per vertex) and `cut_distance` (per face)
/// are the whole surface's, or null.
void run_part(Part& p, const Limits& limits, double threshold, const CutSurface& cut_surface,
              const std::vector<char>* seed, const std::vector<double>* cut_distance) {
  std::vector<char> local_seed;
  std::vector<double> local_distance;
  if (seed)
    for (int v : p.vertex_of) local_seed.push_back((*seed)[size_t(v)]);
  if (cut_distance)
    for (int f : p.face_of) local_distance.push_back((*cut_distance)[size_t(f)]);
  Collapser c(p.r, p.cut, limits, nullptr, cut_surface, p.slab);
  p.moves = c.run(threshold, seed ? &local_seed : nullptr, cut_distance ? &local_distance : nullptr);
  p.flat_flips = c.flat_flips_;
  p.budget_left = c.hand_over(p.alive, p.cut, p.cut_distance, p.deferred);
}

/// Writes the parts' changes back into r: a part changes only faces inside its slab, and
/// the slabs are apart, so no face or vertex is changed by two. Dead faces go (vertices
/// stay, some then unused). `seed` gets the vertices of faces in more than one part (on
/// the slabs' border) and those whose moves a slab refused.
void apply_parts(Result& r, std::vector<char>& cut, std::vector<double>& cut_distance, std::vector<char>& seed,
                 const std::vector<Part*>& parts) {
  const size_t nf = r.faces.size();
  std::vector<int> owner(nf, -1), local_face(nf, -1);  // owner -2: in several parts
  for (size_t i = 0; i < parts.size(); ++i)
    for (size_t l = 0; l < parts[i]->face_of.size(); ++l) {
      const int f = parts[i]->face_of[l];
      owner[f] = owner[f] == -1 ? int(i) : -2;
      local_face[f] = int(l);
    }
  for (const Part* p : parts)
    for (size_t l = 0; l < p->vertex_of.size(); ++l) r.vertices[size_t(p->vertex_of[l])] = p->r.vertices[l];
  seed.assign(r.vertices.size(), 0);
  size_t k = 0;
  const bool sources = !r.face_source.empty();
  for (size_t f = 0; f < nf; ++f) {
    const int i = owner[f];
    if (i >= 0) {
      const Part& p = *parts[size_t(i)];
      const size_t l = size_t(local_face[f]);
      if (!p.alive[l]) continue;
      for (int z = 0; z < 3; ++z) r.faces[k][z] = p.vertex_of[size_t(p.r.faces[l][z])];
      r.line_edge[k] = p.r.line_edge[l];
      cut[k] = p.cut[l];
      cut_distance[k] = p.cut_distance[l];
      if (sources) r.face_source[k] = p.r.face_source[l];
    } else {
      if (i == -2)
        for (int x : r.faces[f]) seed[size_t(x)] = 1;
      r.faces[k] = r.faces[f];
      r.line_edge[k] = r.line_edge[f];
      cut[k] = cut[f];
      cut_distance[k] = cut_distance[f];
      if (sources) r.face_source[k] = r.face_source[f];
    }
    ++k;
  }
  r.faces.resize(k);
  r.line_edge.resize(k);
  cut.resize(k);
  cut_distance.resize(k);
  if (sources) r.face_source.resize(k);
  for (const Part* p : parts)
    for (size_t l = 0; l < p->vertex_of.size(); ++l)
      if (p->deferred[l]) seed[size_t(p->vertex_of[l])] = 1;
}

/// The slivers' median along the longest extent of their centroids: two slabs, each
/// with about half of them.
std::array<Slab, 2> halves(const Result& r, const std::vector<int>& slivers) {
  V3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  std::vector<V3> centroid(slivers.size());
  for (size_t i = 0; i < slivers.size(); ++i) {
    const auto& t = r.faces[slivers[i]];
    for (int k = 0; k < 3; ++k) {
      centroid[i][k] = (r.vertices[t[0]][k] + r.vertices[t[1]][k] + r.vertices[t[2]][k]) / 3;
      lo[k] = std::min(lo[k], centroid[i][k]);
      hi[k] = std::max(hi[k], centroid[i][k]);
    }
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
  std::vector<double> c(slivers.size());
  for (size_t i = 0; i < c.size(); ++i) c[i] = centroid[i][axis];
  std::nth_element(c.begin(), c.begin() + ptrdiff_t(c.size() / 2), c.end());
  const double m = c[c.size() / 2];
  return {Slab{axis, -HUGE_VAL, m}, Slab{axis, m, HUGE_VAL}};
}

int collapse_in_halves(Result& r, const std::vector<char>& cut_in, const Limits& limits, double threshold,
                       const std::vector<int>& slivers, SideWorker* helper, int* flat_flips) {
  const std::array<Slab, 2> slabs = halves(r, slivers);
  std::array<Part, 2> halves_run;
  std::array<FaceTree, 2> trees;  // each half's part of the cut's surface, as the cut left it
  Limits half = limits;
  half.volume_budget /= 2;
  parallel_for(2, 1, [&](size_t i) {
    Part& p = halves_run[i];
    p.slab = slabs[i];
    extract(r, cut_in, p);
    trees[i] = FaceTree(p.r.vertices, p.r.faces, faces_near_cut(p.r, p.cut));
    run_part(p, half, threshold, CutSurface{&trees[i]}, nullptr, nullptr);
  });
  std::vector<char> cut = cut_in, seed;
  std::vector<double> cut_distance(r.faces.size(), 0);
  apply_parts(r, cut, cut_distance, seed, {&halves_run[0], &halves_run[1]});
  // Then the whole surface, for the slivers either half left: those on the border and
  // any a half could not mend alone (its share of the budget spent, or a move it had to
  // refuse), with the budget the halves left.
  for (size_t f = 0; f < r.faces.size(); ++f) {
    const auto& t = r.faces[f];
    if (cut[f] && smallest_angle(r.vertices[t[0]], r.vertices[t[1]], r.vertices[t[2]]) < threshold)
      for (int x : t) seed[size_t(x)] = 1;
  }
  Limits rest = limits;
  for (const Part& p : halves_run) rest.volume_budget -= half.volume_budget - p.budget_left;
  rest.volume_budget = std::max(0.0, rest.volume_budget);
  Collapser c(r, cut, rest, helper, CutSurface{&trees[0], &trees[1]});
  const int moves = halves_run[0].moves + halves_run[1].moves + c.run(threshold, &seed, &cut_distance);
  if (flat_flips) *flat_flips = halves_run[0].flat_flips + halves_run[1].flat_flips + c.flat_flips_;
  c.compact();
  return moves;
}

}  // namespace

int collapse_slivers(Result& r, const std::vector<char>& cut, double sliver_angle_deg, double max_deviation,
                     double max_volume_change, SideWorker* helper, int* parts, int* flat_flips) {
  const double threshold = sliver_angle_deg * kPi / 180;
  const Limits limits = limits_of(r, max_deviation, max_volume_change);
  std::vector<int> slivers;
  for (int f = 0; f < int(r.faces.size()); ++f) {
    const auto& t = r.faces[f];
    if (cut[f] && smallest_angle(r.vertices[t[0]], r.vertices[t[1]], r.vertices[t[2]]) < threshold) slivers.push_back(f);
  }
  // Many slivers: two halves of the surface at once (the same result on one thread).
  if (slivers.size() >= kMinSliversForParts) {
    if (parts) *parts = 2;
    return collapse_in_halves(r, cut, limits, threshold, slivers, helper, flat_flips);
  }
  if (parts) *parts = 1;
  // The tree and the collapser's own tables both only read r.
  FaceTree tree;
  std::optional<Collapser> c;
  auto build_tree = [&] { tree = FaceTree(r.vertices, r.faces, faces_near_cut(r, cut)); };
  auto set_up = [&] {
    c.emplace(r, cut, limits, helper, CutSurface{&tree});
    return true;
  };
  if (helper) {
    helper->run(build_tree, set_up);
  } else {
    build_tree();
    set_up();
  }
  const int n = c->run(threshold);
  if (flat_flips) *flat_flips = c->flat_flips_;
  c->compact();
  return n;
}

}  // namespace mr::surface_union
