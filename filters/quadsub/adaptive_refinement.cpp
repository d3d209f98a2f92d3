#include "quadsub/adaptive_refinement.h"

#include "common/errors.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <unordered_map>
#include <utility>

namespace mr::quadsub {
namespace {

enum State : char { kAbsent = 0, kLeaf = 1, kSplit = 2 };

std::uint64_t edge_key(int a, int b) {
  auto [lo, hi] = std::minmax(a, b);
  return (std::uint64_t(std::uint32_t(lo)) << 32) | std::uint32_t(hi);
}

// One level of the hierarchy: the faces of the uniform scheme at this level that were
// computed (all of them at levels 0 and 1; below, the descendants of the input faces near
// the refinement). `state` says which of them are faces of the adaptive mesh (leaves),
// which were split further, and which lie inside a coarser leaf (absent). The points are the
// uniform scheme's, so a point shared by faces of different levels is one vertex.
struct Level {
  QuadMesh mesh;
  EdgeList creases;
  std::unordered_map<std::uint64_t, std::array<int, 2>> edge_faces;
  std::vector<char> state;
  std::vector<char> marked;      // descends from a selected input polygon
  std::vector<int> parent;       // face of the previous level (-1 at level 0)
  std::vector<int> origin;       // input (level-0) quad it descends from
  std::vector<int> first_child;  // its children are first_child + 0..3 of the next level; -1: not computed

  void index_edges() {
    edge_faces.reserve(2 * mesh.quads.size());
    for (int q = 0; q < int(mesh.quads.size()); ++q)
      for (int s = 0; s < 4; ++s) {
        auto& f = edge_faces.try_emplace(edge_key(mesh.quads[q][s], mesh.quads[q][(s + 1) % 4]),
                                         std::array<int, 2>{-1, -1}).first->second;
        (f[0] < 0 ? f[0] : f[1]) = q;
      }
  }

  // The face across side s of quad q, or -1 on a boundary (or beyond the computed region).
  int across(int q, int s) const {
    const auto& f = edge_faces.at(edge_key(mesh.quads[q][s], mesh.quads[q][(s + 1) % 4]));
    return f[0] == q ? f[1] : f[0];
  }
};

// Thrown when a face farther from the seeds than the computed region allows must be split.
struct NeedsWiderRegion {};

// Rings of input quads (joined through shared vertices) from the seed quads; -1 if unreachable.
std::vector<int> ring_distance(const QuadMesh& m, const std::vector<char>& seed) {
  std::vector<std::vector<int>> faces_at(m.points.size());
  for (int q = 0; q < int(m.quads.size()); ++q)
    for (int v : m.quads[q]) faces_at[v].push_back(q);
  std::vector<int> dist(m.quads.size(), -1), front;
  for (int q = 0; q < int(m.quads.size()); ++q)
    if (seed[q]) { dist[q] = 0; front.push_back(q); }
  for (size_t i = 0; i < front.size(); ++i)
    for (int v : m.quads[front[i]])
      for (int g : faces_at[v])
        if (dist[g] < 0) { dist[g] = dist[front[i]] + 1; front.push_back(g); }
  return dist;
}

class Refinement {
public:
  Refinement(Result level_zero, std::vector<char> marked, const Params& params, const AdaptiveParams& adaptive,
             double diagonal)
      : params_(params), adaptive_(adaptive), diagonal_(diagonal), marked_(std::move(marked)) {
    Level& base = levels_.emplace_back();
    const int n = int(level_zero.mesh.quads.size());
    base.mesh = std::move(level_zero.mesh);
    base.creases = std::move(level_zero.creases);
    base.parent.assign(n, -1);
    base.origin.resize(n);
    std::iota(base.origin.begin(), base.origin.end(), 0);
    base.index_edges();
  }

  // Refines inside a region around the seeds (the input faces refined first); when a
  // ripple or a later level reaches past it, starts again with a wider region.
  void run() {
    reset();
    add_level(0);  // level 1 in full: the error of every input face needs its face point
    std::vector<char> seed(levels_[0].mesh.quads.size(), 0);
    for (int q = 0; q < int(seed.size()); ++q) seed[q] = wants_split(0, q);
    dist0_ = ring_distance(levels_[0].mesh, seed);
    int farthest = 0;
    for (int d : dist0_) farthest = std::max(farthest, d);
    for (int allowed = adaptive_.initial_region_rings;; allowed = 2 * allowed + 2) {
      // Children of a face at level l are exact when its 2-ring at level l is: that ring
      // reaches one input quad farther, so each level below 1 costs one ring of margin.
      allowed_ = allowed;
      region_ = allowed + params_.iterations + 1;
      // Once the region holds every reachable quad, compute everything (other components
      // too), so the widening always ends.
      restricted_ = region_ < farthest;
      try {
        refine_levels();
        return;
      } catch (const NeedsWiderRegion&) {
        ++restarts_;
        reset();
      }
    }
  }

  AdaptiveResult output() const {
    AdaptiveResult r;
    r.refined_per_level = refined_;
    r.balance_refinements = balance_refinements_;
    r.region_restarts = restarts_;
    for (const Level& lv : levels_) r.hierarchy_faces += int(lv.mesh.quads.size());
    QuadMesh& out = r.mesh;
    for (int l = 0; l < int(levels_.size()); ++l) {
      const Level& lv = levels_[l];
      for (int q = 0; q < int(lv.mesh.quads.size()); ++q) {
        if (lv.state[q] != kLeaf) continue;
        const int faces_before = int(out.quads.size() + r.triangles.size());
        emit_leaf(l, q, r);
        const int added = int(out.quads.size() + r.triangles.size()) - faces_before;
        if (added > 1) r.transition_faces += added;
        r.levels = std::max(r.levels, l);
      }
    }
    compact_points(r);
    return r;
  }

private:
  // Back to the input faces as leaves; levels 0 and 1 are kept, deeper ones recomputed.
  void reset() {
    if (levels_.size() > 2) levels_.resize(2);
    levels_[0].state.assign(levels_[0].mesh.quads.size(), kLeaf);
    levels_[0].marked = marked_;
    if (levels_.size() > 1) {
      levels_[1].state.assign(levels_[1].mesh.quads.size(), kAbsent);
      levels_[1].marked.assign(levels_[1].mesh.quads.size(), 0);
      levels_[1].first_child.assign(levels_[1].mesh.quads.size(), -1);
    }
    refined_.clear();
    balance_refinements_ = 0;
  }

  void refine_levels() {
    for (int l = 0; l < params_.iterations; ++l) {
      if (int(levels_.size()) < l + 2) add_level(l);
      refined_.push_back(0);
      std::vector<int> chosen;
      for (int q = 0; q < int(levels_[l].mesh.quads.size()); ++q)
        if (levels_[l].state[q] == kLeaf && wants_split(l, q)) chosen.push_back(q);
      if (chosen.empty()) { refined_.pop_back(); levels_.resize(l + 1); break; }
      for (int q : chosen) split(l, q, false);
      close_faces_split_all_around();
    }
  }

  // Level l + 1 from level l: one uniform step on the faces of level l inside the region.
  void add_level(int l) {
    Level& coarse = levels_[l];
    QuadMesh part;
    part.points = coarse.mesh.points;  // keeps every index valid at every level
    std::vector<int> source;
    for (int q = 0; q < int(coarse.mesh.quads.size()); ++q)
      if (l == 0 || !restricted_ || (dist0_[coarse.origin[q]] >= 0 && dist0_[coarse.origin[q]] <= region_)) {
        part.quads.push_back(coarse.mesh.quads[q]);
        source.push_back(q);
      }
    Level fine;
    fine.mesh = subdivide_step(part, coarse.creases, params_, &fine.creases);
    const int n = int(fine.mesh.quads.size());
    fine.state.assign(n, kAbsent);
    fine.marked.assign(n, 0);
    fine.parent.resize(n);
    fine.origin.resize(n);
    fine.first_child.assign(n, -1);
    coarse.first_child.assign(coarse.mesh.quads.size(), -1);
    for (int j = 0; j < int(source.size()); ++j) {
      coarse.first_child[source[j]] = 4 * j;
      for (int k = 0; k < 4; ++k) {
        fine.parent[4 * j + k] = source[j];
        fine.origin[4 * j + k] = coarse.origin[source[j]];
      }
    }
    fine.index_edges();
    levels_.push_back(std::move(fine));
  }

  // The children of q, computed and exact; throws when q lies beyond the region.
  int children_of(int l, int q) const {
    const int first = levels_[l].first_child[q];
    if (first < 0) throw NeedsWiderRegion{};
    return first;
  }

  bool wants_split(int l, int q) const {
    switch (adaptive_.refine) {
      case RefineFaces::All: return true;  // (subdivide_adaptive runs the uniform scheme for All)
      case RefineFaces::Selected: return levels_[l].marked[q] != 0;
      case RefineFaces::ErrorAbove: {
        const auto& c = levels_[l].mesh.quads[q];
        const auto& p = levels_[l].mesh.points;
        const Point3 bilinear_centre = (p[c[0]] + p[c[1]] + p[c[2]] + p[c[3]]) * 0.25;
        const QuadMesh& fine = levels_[l + 1].mesh;
        const Point3& face_point = fine.points[fine.quads[children_of(l, q)][2]];
        return (face_point - bilinear_centre).Norm() > adaptive_.error_threshold * diagonal_;
      }
    }
    return false;
  }

  // The adaptive-mesh face covering quad g of level l: g itself or its nearest present ancestor.
  std::pair<int, int> covering_face(int l, int g) const {
    while (levels_[l].state[g] == kAbsent) { g = levels_[l].parent[g]; --l; }
    return {l, g};
  }

  // Splits leaf q of level l into its four children, after splitting every coarser edge
  // neighbour (recursively), so that faces sharing an edge never differ by two levels.
  void split(int l, int q, bool for_balance) {
    if (levels_[l].state[q] != kLeaf) return;
    const int d = dist0_[levels_[l].origin[q]];
    if (restricted_ && (d < 0 || d > allowed_)) throw NeedsWiderRegion{};
    for (int s = 0; s < 4; ++s) {
      const int g = levels_[l].across(q, s);
      if (g < 0) continue;
      while (true) {
        const auto [lg, cg] = covering_face(l, g);
        if (lg >= l) break;
        split(lg, cg, true);  // the coarser neighbour first; it may itself need a ripple
      }
    }
    const int first = children_of(l, q);
    Level& lv = levels_[l];
    Level& fine = levels_[l + 1];
    lv.state[q] = kSplit;
    for (int k = 0; k < 4; ++k) {
      fine.state[first + k] = kLeaf;
      fine.marked[first + k] = for_balance ? 0 : lv.marked[q];
    }
    ++refined_[l];
    balance_refinements_ += for_balance;
  }

  int hanging_mask(int l, int q) const {
    int mask = 0;
    for (int s = 0; s < 4; ++s) {
      const int g = levels_[l].across(q, s);
      if (g >= 0 && levels_[l].state[g] == kSplit) mask |= 1 << s;
    }
    return mask;
  }

  // A leaf whose four neighbours are all split is split as well: its "transition" would
  // be its four children anyway, and this keeps their level right.
  void close_faces_split_all_around() {
    for (bool changed = true; changed;) {
      changed = false;
      for (int l = 0; l + 1 < int(levels_.size()); ++l)
        for (int q = 0; q < int(levels_[l].mesh.quads.size()); ++q)
          if (levels_[l].state[q] == kLeaf && hanging_mask(l, q) == 15) {
            split(l, q, true);
            changed = true;
          }
    }
  }

  // The leaf as one quad, or closed around its hanging edge points by a template:
  // one hanging side -> 2 quads + 1 triangle; two adjacent -> 3 quads; two opposite -> 2 quads;
  // three -> 3 quads + 1 triangle. The templates use the face's own face point, a point of
  // the uniform scheme, so they are on the same surface as the refined neighbours.
  void emit_leaf(int l, int q, AdaptiveResult& r) const {
    const auto c = levels_[l].mesh.quads[q];
    const int mask = hanging_mask(l, q);
    auto quad = [&](int a, int b, int cc, int d) { r.mesh.quads.push_back({a, b, cc, d}); r.quad_level.push_back(l); };
    auto tri = [&](int a, int b, int cc) { r.triangles.push_back({a, b, cc}); r.triangle_level.push_back(l); };
    if (mask == 0) { quad(c[0], c[1], c[2], c[3]); return; }
    const auto& children = levels_[l + 1].mesh.quads;
    const int first = levels_[l].first_child[q];  // computed: a neighbour was split
    const int f = children[first][2];
    auto C = [&](int s) { return c[(s % 4 + 4) % 4]; };
    auto M = [&](int s) { return children[first + (s % 4 + 4) % 4][1]; };  // edge point of side s
    auto has = [&](int s) { return (mask >> ((s % 4 + 4) % 4)) & 1; };
    const int count = has(0) + has(1) + has(2) + has(3);
    if (count == 4) {
      for (int k = 0; k < 4; ++k) quad(C(k), M(k), f, M(k - 1));
      return;
    }
    // s: the first hanging side of the run of hanging sides (the one after a free side)
    int s = 0;
    while (!(has(s) && !has(s - 1))) ++s;
    if (count == 1) {
      quad(C(s), M(s), f, C(s + 3));
      quad(M(s), C(s + 1), C(s + 2), f);
      tri(f, C(s + 2), C(s + 3));
    } else if (count == 2 && has(s + 1)) {
      quad(M(s), C(s + 1), M(s + 1), f);
      quad(C(s), M(s), f, C(s + 3));
      quad(f, M(s + 1), C(s + 2), C(s + 3));
    } else if (count == 2) {  // opposite sides s and s + 2
      quad(C(s), M(s), M(s + 2), C(s + 3));
      quad(M(s), C(s + 1), C(s + 2), M(s + 2));
    } else {  // sides s, s + 1, s + 2
      quad(M(s), C(s + 1), M(s + 1), f);
      quad(f, M(s + 1), C(s + 2), M(s + 2));
      quad(C(s), M(s), f, C(s + 3));
      tri(f, M(s + 2), C(s + 3));
    }
  }

  // Keeps the input's points (and the level-0 split points) at their indices, drops the
  // uniform scheme's points no face uses.
  void compact_points(AdaptiveResult& r) const {
    const auto& all = levels_.back().mesh.points;
    const int kept = int(levels_.front().mesh.points.size());
    std::vector<int> index(all.size(), -1);
    for (const auto& q : r.mesh.quads)
      for (int v : q) index[v] = 0;
    for (const auto& t : r.triangles)
      for (int v : t) index[v] = 0;
    r.mesh.points.clear();
    for (int v = 0; v < int(all.size()); ++v)
      if (v < kept || index[v] == 0) {
        index[v] = int(r.mesh.points.size());
        r.mesh.points.push_back(all[v]);
      }
    for (auto& q : r.mesh.quads)
      for (int& v : q) v = index[v];
    for (auto& t : r.triangles)
      for (int& v : t) v = index[v];
  }

  const Params& params_;
  const AdaptiveParams& adaptive_;
  const double diagonal_;
  const std::vector<char> marked_;
  std::vector<int> dist0_;    // rings of input quads from the seeds
  int allowed_ = 0;           // faces split must descend from input quads this close to the seeds
  int region_ = 0;            // levels below 1 are computed for input quads this close
  bool restricted_ = false;
  int restarts_ = 0;
  std::vector<Level> levels_;
  std::vector<int> refined_;
  int balance_refinements_ = 0;
};

// The uniform scheme's result in the adaptive result's terms: every face at the last level.
AdaptiveResult as_adaptive(Result uniform) {
  AdaptiveResult r;
  r.mesh = std::move(uniform.mesh);
  r.quad_level.assign(r.mesh.quads.size(), uniform.levels);
  r.vertices_in = uniform.vertices_in;
  r.faces_in = uniform.faces_in;
  r.extraordinary_vertices = uniform.extraordinary_vertices;
  r.crease_edges_in = uniform.crease_edges_in;
  r.cusps = uniform.cusps;
  r.levels = uniform.levels;
  const int quads_in = int(r.mesh.quads.size() >> (2 * uniform.levels));  // after splitting non-quads
  for (int l = 0; l < uniform.levels; ++l) {
    r.refined_per_level.push_back(quads_in << (2 * l));
    r.hierarchy_faces += quads_in << (2 * l);
  }
  r.hierarchy_faces += int(r.mesh.quads.size());
  return r;
}

}  // namespace

AdaptiveResult subdivide_adaptive(const std::vector<Point3>& points, const std::vector<std::vector<int>>& polygons,
                                  const EdgeList& marked_creases, const std::vector<char>& selected_polygons,
                                  const Params& params, const AdaptiveParams& adaptive) {
  if (adaptive.refine == RefineFaces::ErrorAbove && !(adaptive.error_threshold > 0 && std::isfinite(adaptive.error_threshold)))
    throw InvalidInput("error_threshold must be > 0, got " + std::to_string(adaptive.error_threshold));
  if (adaptive.initial_region_rings < 0)
    throw InvalidInput("initial_region_rings must be >= 0, got " + std::to_string(adaptive.initial_region_rings));
  if (adaptive.refine == RefineFaces::All) return as_adaptive(subdivide(points, polygons, marked_creases, params));
  if (adaptive.refine == RefineFaces::Selected) {
    if (selected_polygons.size() != polygons.size())
      throw InvalidInput("the selection has " + std::to_string(selected_polygons.size()) + " entries for " +
                         std::to_string(polygons.size()) + " polygons");
    if (std::none_of(selected_polygons.begin(), selected_polygons.end(), [](char s) { return s != 0; }))
      throw InvalidInput("no face is selected: select the faces to refine, or refine all faces or by error");
  }
  std::vector<int> polygon_of_quad;
  Result zero = prepare_level_zero(points, polygons, marked_creases, params, &polygon_of_quad);
  std::vector<char> marked(zero.mesh.quads.size(), 0);
  if (adaptive.refine == RefineFaces::Selected)
    for (size_t q = 0; q < marked.size(); ++q) marked[q] = selected_polygons[polygon_of_quad[q]] != 0;
  Box3 box;
  for (const auto& p : points) box.Add(p);

  const int vertices_in = zero.vertices_in, faces_in = zero.faces_in;
  const int extraordinary = zero.extraordinary_vertices, crease_edges = zero.crease_edges_in, cusps = zero.cusps;
  Refinement refinement(std::move(zero), std::move(marked), params, adaptive, box.Diag());
  refinement.run();
  AdaptiveResult out = refinement.output();
  out.vertices_in = vertices_in;
  out.faces_in = faces_in;
  out.extraordinary_vertices = extraordinary;
  out.crease_edges_in = crease_edges;
  out.cusps = cusps;
  return out;
}

}  // namespace mr::quadsub
