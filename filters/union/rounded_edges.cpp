#include "union/rounded_edges.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>

#include "common/union_find.h"
#include "union/exact.h"
#include "union/face_clearance.h"
#include "union/vec3.h"

namespace mr::surface_union {

namespace {

class ClusterMerger {
public:
  ClusterMerger(Result& r, std::vector<char>& cut) : r_(r), cut_(cut) {}

  int run() {
    tiny_ = rounding_slack(r_);
    // Most unions have no such edge: the stars are built only then.
    if (!(tiny_ > 0) || close_edges().empty()) return 0;
    alive_.assign(r_.faces.size(), 1);
    vf_.assign(r_.vertices.size(), {});
    for (int f = 0; f < int(r_.faces.size()); ++f)
      for (int v : r_.faces[size_t(f)]) vf_[size_t(v)].push_back(f);
    int merged = 0;
    for (bool again = true; again;) {
      again = false;
      // Whole clusters (ends joined by close edges) first: where three or more crossings
      // lie within a few units, a merge of one edge can leave a face with two corners at
      // one place that the next merge then fails the link condition on (fuzz seed 100166).
      // Where a cluster cannot go as a whole, its edges one by one, shortest first.
      const auto edges = close_edges();
      for (const auto& members : clusters(edges))
        if (members.size() > 2 && collapse(members)) {
          merged += int(members.size()) - 1;
          again = true;
        }
      for (const auto& [length, u, w] : close_edges())
        if (edge_exists(u, w) && collapse({u, w})) {
          ++merged;
          again = true;
        }
    }
    if (merged > 0) compact();
    return merged;
  }

private:
  const V3& at(int v) const { return r_.vertices[size_t(v)]; }
  /// Ends within tiny_ of each other in every coordinate.
  bool close(int u, int w) const { return within_slack(at(u), at(w), tiny_); }
  /// Edges of live cut faces whose ends are close: (length, lower end, higher end), sorted.
  /// (One end at least is a crossing, so the edge's faces are cut faces.)
  std::vector<std::tuple<double, int, int>> close_edges() const {
    std::vector<std::tuple<double, int, int>> out;
    for (size_t f = 0; f < r_.faces.size(); ++f)
      if (cut_[f] && (alive_.empty() || alive_[f]))
        for (int z = 0; z < 3; ++z) {
          const int u = r_.faces[f][size_t(z)], w = r_.faces[f][size_t((z + 1) % 3)];
          if (close(u, w)) out.emplace_back(norm(sub3(at(u), at(w))), std::min(u, w), std::max(u, w));
        }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  /// Vertices joined by close edges, each cluster sorted, in the order of its lowest id.
  std::vector<std::vector<int>> clusters(const std::vector<std::tuple<double, int, int>>& edges) const {
    std::vector<int> ends;
    for (const auto& [length, u, w] : edges) { ends.push_back(u); ends.push_back(w); }
    std::sort(ends.begin(), ends.end());
    ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
    auto index = [&](int v) { return int(std::lower_bound(ends.begin(), ends.end(), v) - ends.begin()); };
    UnionFind uf(int(ends.size()));
    for (const auto& [length, u, w] : edges) uf.unite(index(u), index(w));
    std::vector<std::vector<int>> by_root(ends.size());
    for (size_t i = 0; i < ends.size(); ++i) by_root[size_t(uf.find(int(i)))].push_back(ends[i]);
    std::vector<std::vector<int>> out;
    for (auto& c : by_root)
      if (!c.empty()) out.push_back(std::move(c));
    std::sort(out.begin(), out.end());
    return out;
  }
  bool has(int f, int v) const {
    const auto& t = r_.faces[size_t(f)];
    return t[0] == v || t[1] == v || t[2] == v;
  }
  bool edge_exists(int u, int w) const {
    for (int f : vf_[size_t(u)])
      if (alive_[size_t(f)] && has(f, w)) return true;
    return false;
  }

  /// Merges `members` (sorted) into one of them, the first for which the result is a
  /// closed manifold around it and the moved faces are clear (moved_faces_clear).
  bool collapse(const std::vector<int>& members) {
    auto member = [&](int v) { return std::binary_search(members.begin(), members.end(), v); };
    around_.clear();
    for (int m : members)
      for (int f : vf_[size_t(m)])
        if (alive_[size_t(f)]) around_.push_back(f);
    std::sort(around_.begin(), around_.end());
    around_.erase(std::unique(around_.begin(), around_.end()), around_.end());
    dying_.clear();
    kept_.clear();
    for (int f : around_) {
      int n = 0;
      for (int v : r_.faces[size_t(f)]) n += member(v);
      (n >= 2 ? dying_ : kept_).push_back(f);
    }
    take_bubbles(member);
    if (!manifold_after(member) || !bubble_corners_closed(member)) return false;
    // A side (m, x) of any face here is the side (rep, x) afterwards: a line edge if any was.
    std::vector<std::pair<int, bool>> line_at;  // (x, flag)
    for (int f : around_)
      for (int z = 0; z < 3; ++z) {
        const int a = r_.faces[size_t(f)][size_t(z)], b = r_.faces[size_t(f)][size_t((z + 1) % 3)];
        if (member(a) != member(b)) line_at.push_back({member(a) ? b : a, r_.line_edge[size_t(f)][size_t(z)]});
      }
    std::sort(line_at.begin(), line_at.end());
    auto line_to = [&](int x) {
      const auto it = std::lower_bound(line_at.begin(), line_at.end(), std::make_pair(x, true));
      return it != line_at.end() && it->first == x;
    };
    old_.clear();
    for (int f : kept_) old_.push_back(r_.faces[size_t(f)]);
    // Filed before any face is renamed: a box filed off by a few units could miss a neighbour.
    if (!grid_ && std::any_of(members.begin(), members.end(), [&](int m) { return at(m) != at(members[0]); }))
      grid_.emplace(r_.vertices, r_.faces);
    dying_.insert(dying_.end(), bubble_.begin(), bubble_.end());
    for (int rep : members) {
      for (int f : dying_) alive_[size_t(f)] = 0;
      for (int f : kept_)
        for (int& v : r_.faces[size_t(f)])
          if (member(v)) v = rep;
      saved_star_ = vf_[size_t(rep)];
      vf_[size_t(rep)] = kept_;  // what the fold test walks
      const bool clear = moved_faces_clear(rep);
      vf_[size_t(rep)] = saved_star_;
      if (clear) {
        for (int m : members) vf_[size_t(m)].clear();
        vf_[size_t(rep)] = kept_;
        if (grid_) {
          for (int f : kept_) grid_->add(f);
          for (int f : dying_) grid_->remove(f);
        }
        for (int f : kept_)
          for (int z = 0; z < 3; ++z) {
            const auto& t = r_.faces[size_t(f)];
            const int a = t[size_t(z)], b = t[size_t((z + 1) % 3)];
            if (a == rep || b == rep) r_.line_edge[size_t(f)][size_t(z)] = line_to(a == rep ? b : a);
          }
        return true;
      }
      for (size_t i = 0; i < kept_.size(); ++i) r_.faces[size_t(kept_[i])] = old_[i];
      for (int f : dying_) alive_[size_t(f)] = 1;
    }
    return false;
  }

  /// Kept faces that become one triangle turned both ways, (c, a, b) and (c, b, a), move
  /// from kept_ to bubble_: two sheets of a bubble without volume, which the members, a few
  /// units apart, held open (fuzz seed 117185 with --nonconvex --transform: blobs nearly
  /// coinciding far from the origin; the merge was refused, and two faces kept two corners
  /// at one place through the sliver step). The pair goes with the dying faces.
  template <class Member>
  void take_bubbles(Member member) {
    bubble_.clear();
    std::vector<std::tuple<int, int, size_t>> sides;  // (a, b, index in kept_): the side opposite the member
    for (size_t i = 0; i < kept_.size(); ++i) {
      const auto& t = r_.faces[size_t(kept_[i])];
      int z = 0;
      while (!member(t[size_t(z)])) ++z;
      sides.emplace_back(t[size_t((z + 1) % 3)], t[size_t((z + 2) % 3)], i);
    }
    std::sort(sides.begin(), sides.end());
    std::vector<char> paired(kept_.size(), 0);
    for (const auto& [a, b, i] : sides) {
      if (paired[i]) continue;
      for (auto it = std::lower_bound(sides.begin(), sides.end(), std::make_tuple(b, a, size_t(0)));
           it != sides.end() && std::get<0>(*it) == b && std::get<1>(*it) == a; ++it)
        if (!paired[std::get<2>(*it)] && std::get<2>(*it) != i) {
          paired[i] = paired[std::get<2>(*it)] = 1;
          break;
        }
    }
    size_t k = 0;
    for (size_t i = 0; i < kept_.size(); ++i) {
      if (paired[i]) bubble_.push_back(kept_[i]);
      else kept_[k++] = kept_[i];
    }
    kept_.resize(k);
  }

  /// Without the bubble's faces, every corner of them but the members keeps a closed
  /// manifold star (its link one loop, the members counted as one vertex), or none at all.
  template <class Member>
  bool bubble_corners_closed(Member member) const {
    auto gone = [&](int f) {
      return std::find(dying_.begin(), dying_.end(), f) != dying_.end() ||
             std::find(bubble_.begin(), bubble_.end(), f) != bubble_.end();
    };
    for (int f : bubble_)
      for (int x : r_.faces[size_t(f)]) {
        if (member(x)) continue;
        std::vector<std::pair<int, int>> link;  // the sides opposite x, members as -1
        for (int g : vf_[size_t(x)]) {
          if (!alive_[size_t(g)] || gone(g)) continue;
          const auto& t = r_.faces[size_t(g)];
          int z = 0;
          while (t[size_t(z)] != x) ++z;
          auto id = [&](int v) { return member(v) ? -1 : v; };
          link.push_back({id(t[size_t((z + 1) % 3)]), id(t[size_t((z + 2) % 3)])});
        }
        if (!link.empty() && !one_loop(link)) return false;
      }
    return true;
  }

  /// The sides (a -> b) form one cycle of at least three: each corner once as a start and
  /// once as an end, and following them from the first comes back after all.
  static bool one_loop(std::vector<std::pair<int, int>> link) {
    if (link.size() < 3) return false;
    std::vector<int> out, in;
    for (const auto& [a, b] : link) { out.push_back(a); in.push_back(b); }
    std::sort(out.begin(), out.end());
    std::sort(in.begin(), in.end());
    if (out != in || std::adjacent_find(out.begin(), out.end()) != out.end()) return false;
    std::sort(link.begin(), link.end());
    int x = link[0].first;
    for (size_t n = 0; n < link.size(); ++n) {
      x = std::lower_bound(link.begin(), link.end(), std::make_pair(x, std::numeric_limits<int>::min()))->second;
      if (x == link[0].first) return n + 1 == link.size();
    }
    return false;
  }

  /// With the members one vertex c, the kept faces around it (each with one member corner)
  /// leave a closed manifold: every edge (c, x) has one face each way, and the sides
  /// opposite c form one cycle of at least three (c's link is a single loop). Faces away
  /// from c keep their edges: a dying face has at most one corner that is not a member.
  template <class Member>
  bool manifold_after(Member member) const {
    std::vector<std::pair<int, int>> link;  // a -> b opposite c
    for (int f : kept_) {
      const auto& t = r_.faces[size_t(f)];
      int z = 0;
      while (!member(t[size_t(z)])) ++z;
      link.push_back({t[size_t((z + 1) % 3)], t[size_t((z + 2) % 3)]});
    }
    return one_loop(std::move(link));
  }

  /// The kept faces, members renamed to `rep` (old_ holds them before), keep their turn in
  /// the projection across their largest normal component, strictly, so none turns over or
  /// degenerates (one without area before has no turn to keep); none folds onto a neighbour
  /// across a side (coplanar, on the same side of it); and none meets another face but along
  /// what they share (exact; face_clearance.h).
  /// Faces whose corners stayed where they were are left out of the first two tests.
  bool moved_faces_clear(int rep) {
    moved_.clear();
    for (size_t i = 0; i < kept_.size(); ++i)
      for (int v : old_[i])
        if (at(v) != at(rep) && !has(kept_[i], v)) moved_.push_back(int(i));
    moved_.erase(std::unique(moved_.begin(), moved_.end()), moved_.end());
    if (moved_.empty()) return true;  // all members at one place: no face changes shape
    for (int i : moved_) {
      const int f = kept_[size_t(i)];
      const auto& t = r_.faces[size_t(f)];
      V3 q[3], old_q[3];
      for (int z = 0; z < 3; ++z) {
        q[z] = at(t[size_t(z)]);
        old_q[z] = at(old_[size_t(i)][size_t(z)]);
      }
      const int k = largest_normal_axis(old_q), a = (k + 1) % 3, b = (k + 2) % 3;
      // The turn is kept in the first projection, from k's on, where the face had one. One
      // without area in all three (corners on one line, as rounding can leave them) has no
      // turn to keep: it may come out either way or stay flat, and the fold and crossing
      // tests below still hold it (fuzz seed 112943: four crossings within a few units, each
      // merge refused for such a face, left two faces with two corners at one place).
      for (int n = 0; n < 3; ++n) {
        const int pa = (k + n + 1) % 3, pb = (k + n + 2) % 3;
        const int before = orient2d(old_q[0].data(), old_q[1].data(), old_q[2].data(), pa, pb);
        if (before == 0) continue;
        if (orient2d(q[0].data(), q[1].data(), q[2].data(), pa, pb) != before) return false;
        break;
      }
      // Folds: across each side (x, y), the neighbour's third corner coplanar with the
      // face and on the side of xy where the face's own third corner is. One the face had
      // before the merge, across the same side, does not refuse it (nearly coincident
      // sheets have such pairs where rounding put their points on one lattice): the merge
      // adds no fold.
      auto folds = [&](int x, int y, int own, int c) {
        if (orient3d(at(x).data(), at(y).data(), at(own).data(), at(c).data()) != 0) return false;
        return orient2d(at(x).data(), at(y).data(), at(own).data(), a, b) *
                   orient2d(at(x).data(), at(y).data(), at(c).data(), a, b) >= 0;
      };
      const auto& was = old_[size_t(i)];
      for (int z = 0; z < 3; ++z) {
        const int x = t[size_t(z)], y = t[size_t((z + 1) % 3)], own = t[size_t((z + 2) % 3)];
        for (int g : vf_[size_t(x)]) {
          if (!alive_[size_t(g)] || g == f || !has(g, y)) continue;
          int c = -1;
          for (int v : r_.faces[size_t(g)])
            if (v != x && v != y) c = v;
          if (c < 0) return false;  // (a face with a repeated corner: not one this step makes)
          if (folds(x, y, own, c) && !folds(was[size_t(z)], was[size_t((z + 1) % 3)], was[size_t((z + 2) % 3)], c))
            return false;
        }
      }
    }
    // Crossings: the moved faces against the faces near them and against the other kept
    // faces (kept faces are filed at their old boxes, a few units from the new ones). A
    // kept face that did not move keeps its shape, and its corner at rep sits where its
    // member did, so what it meets does not change. A pair that met before the merge
    // already (rounding made the arrangement cross, where sheets nearly coincide) does not
    // refuse it: the merge adds no crossing.
    auto corners = [&](const std::array<int, 3>& t, V3 q[3]) {
      for (int z = 0; z < 3; ++z) q[z] = at(t[size_t(z)]);
    };
    // Kept face i and face u (as they were) met before the merge.
    auto met_before = [&](size_t i, const std::array<int, 3>& u) {
      V3 oq[3], uq[3];
      corners(old_[i], oq);
      corners(u, uq);
      return triangles_meet(old_[i], oq, u, uq);
    };
    for (int i : moved_) {
      const auto& t = r_.faces[size_t(kept_[size_t(i)])];
      V3 q[3];
      corners(t, q);
      V3 lo = q[0], hi = q[0];
      for (int z = 1; z < 3; ++z)
        for (int m = 0; m < 3; ++m) { lo[m] = std::min(lo[m], q[z][m]); hi[m] = std::max(hi[m], q[z][m]); }
      grid_->near(lo, hi, near_);
      for (int g : near_) {
        if (!alive_[size_t(g)] || std::binary_search(around_.begin(), around_.end(), g)) continue;
        const auto& u = r_.faces[size_t(g)];
        V3 gq[3];
        corners(u, gq);
        if (triangles_meet(t, q, u, gq) && !met_before(size_t(i), u)) return false;
      }
      for (size_t j = 0; j < kept_.size(); ++j) {
        // (Two moved faces: the pair once, from the later.)
        if (int(j) == i || (int(j) > i && std::binary_search(moved_.begin(), moved_.end(), int(j)))) continue;
        const auto& u = r_.faces[size_t(kept_[j])];
        V3 uq[3];
        corners(u, uq);
        if (triangles_meet(t, q, u, uq) && !met_before(size_t(i), old_[j])) return false;
      }
    }
    return true;
  }

  void compact() {
    std::vector<int> index(r_.vertices.size(), -1);
    std::vector<V3> vertices;
    size_t k = 0;
    for (size_t f = 0; f < r_.faces.size(); ++f) {
      if (!alive_[f]) continue;
      for (int& v : r_.faces[f]) {
        if (index[size_t(v)] < 0) {
          index[size_t(v)] = int(vertices.size());
          vertices.push_back(at(v));
        }
        v = index[size_t(v)];
      }
      r_.faces[k] = r_.faces[f];
      r_.line_edge[k] = r_.line_edge[f];
      if (!r_.face_source.empty()) r_.face_source[k] = r_.face_source[f];
      cut_[k] = cut_[f];
      ++k;
    }
    r_.faces.resize(k);
    r_.line_edge.resize(k);
    if (!r_.face_source.empty()) r_.face_source.resize(k);
    cut_.resize(k);
    r_.vertices = std::move(vertices);
  }

  Result& r_;
  std::vector<char>& cut_;
  std::vector<char> alive_;
  std::vector<std::vector<int>> vf_;
  std::vector<int> around_, dying_, kept_, bubble_, moved_, near_, saved_star_;  // scratch of collapse()
  std::vector<std::array<int, 3>> old_;                    // the kept faces before renaming
  std::optional<FaceGrid> grid_;                           // built at the first merge that moves faces
  double tiny_ = 0;                                        // 4 units in the last place of the largest coordinate
};

}  // namespace

int merge_rounded_together(Result& r, std::vector<char>& cut) { return ClusterMerger(r, cut).run(); }

double rounding_slack(const Result& r) {
  double largest = 0;
  for (const auto& p : r.vertices)
    for (double x : p) largest = std::max(largest, std::fabs(x));
  return 4 * (std::nextafter(largest, std::numeric_limits<double>::infinity()) - largest);
}

}  // namespace mr::surface_union
