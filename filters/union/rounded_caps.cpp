#include "union/rounded_caps.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "union/exact.h"
#include "union/face_clearance.h"
#include "union/rounded_edges.h"
#include "union/vec3.h"

namespace mr::surface_union {

namespace {

using Face = std::array<int, 3>;

class CapSplitter {
public:
  CapSplitter(Result& r, std::vector<char>& cut) : r_(r), cut_(cut), tiny_(rounding_slack(r)) {}

  int run() {
    if (!(tiny_ > 0)) return 0;
    std::vector<int> caps = find_caps();
    if (caps.empty()) return 0;  // (nearly every union: nothing else is built)
    vf_.assign(r_.vertices.size(), {});
    for (int f = 0; f < int(r_.faces.size()); ++f)
      for (int v : r_.faces[size_t(f)]) vf_[size_t(v)].push_back(f);
    grid_.emplace(r_.vertices, r_.faces);
    int removed = 0;
    // A removal can leave a cap where the neighbour was one too: tried again, a few times.
    for (int round = 0; round < 4 && !caps.empty(); ++round) {
      const int before = removed;
      for (int f : caps) {
        int z = -1;
        if (cap_side(f, z)) removed += remove_cap(f, z);
      }
      if (removed == before) break;
      caps = find_caps();
    }
    return removed;
  }

private:
  const V3& at(int v) const { return r_.vertices[size_t(v)]; }
  bool close(int u, int w) const { return within_slack(at(u), at(w), tiny_); }
  /// Where along side (a, b) the point c projects, as a fraction of the side.
  double along(int a, int b, int c) const {
    const V3 ab = sub3(at(b), at(a));
    return dot(sub3(at(c), at(a)), ab) / dot(ab, ab);
  }
  /// Face f is a cap over its side z (t[z] -> t[z+1]): the third corner within tiny_ of
  /// the side's line, strictly between its ends and not close to either (that is an edge
  /// rounding left without length, merge_rounded_together's).
  bool cap_side(int f, int& z_out) const {
    const Face& t = r_.faces[size_t(f)];
    for (int z = 0; z < 3; ++z) {
      const int a = t[size_t(z)], b = t[size_t((z + 1) % 3)], c = t[size_t((z + 2) % 3)];
      const V3 ab = sub3(at(b), at(a)), ac = sub3(at(c), at(a));
      const double l2 = dot(ab, ab), s = dot(ac, ab);
      if (!(l2 > 0) || !(s > 0) || !(s < l2) || close(a, c) || close(b, c)) continue;
      const V3 n = cross(ab, ac);
      if (dot(n, n) <= tiny_ * tiny_ * l2) {
        z_out = z;
        return true;
      }
    }
    return false;
  }
  std::vector<int> find_caps() const {
    std::vector<int> out;
    for (int f = 0; f < int(r_.faces.size()); ++f) {
      int z = -1;
      if (cut_[size_t(f)] && cap_side(f, z)) out.push_back(f);
    }
    return out;
  }
  /// The face with directed side p -> q, and that side's index (-1 if none).
  int across(int p, int q, int& side) const {
    for (int h : vf_[size_t(p)]) {
      const Face& t = r_.faces[size_t(h)];
      for (int z = 0; z < 3; ++z)
        if (t[size_t(z)] == p && t[size_t((z + 1) % 3)] == q) {
          side = z;
          return h;
        }
    }
    return -1;
  }
  /// Face h's side p -> q split at s: (p, s, x) and (s, q, x), for `slots` (h's own first).
  struct Split {
    int h, p, q, s, free_slot;
  };

  void set_face(int slot, const Face& t) {
    for (int v : r_.faces[size_t(slot)]) {
      auto& list = vf_[size_t(v)];
      list.erase(std::find(list.begin(), list.end(), slot));
    }
    r_.faces[size_t(slot)] = t;
    for (int v : t) vf_[size_t(v)].push_back(slot);
  }

  /// Cap f over its side z; returns 1 if it was removed.
  int remove_cap(int f, int z) {
    const Face tf = r_.faces[size_t(f)];
    const int a = tf[size_t(z)], b = tf[size_t((z + 1) % 3)], c = tf[size_t((z + 2) % 3)];
    int y = -1;
    const int g = across(b, a, y);
    if (g < 0 || g == f) return 0;
    const int d = r_.faces[size_t(g)][size_t((y + 2) % 3)];
    if (d == c) return 0;
    int zg = -1;
    const bool double_cap = cap_side(g, zg) && zg == y;
    std::vector<int> removed{f};
    std::vector<Split> splits;
    if (!double_cap) {
      splits.push_back({g, b, a, c, f});
    } else {
      // Along a -> b: the chain a -> c -> b of the faces outside f, and b -> d -> a of those
      // outside g; each side that holds the other chain's corner is split at it.
      const double tc = along(a, b, c), td = along(a, b, d);
      if (close(c, d)) return flip_to_apexes(f, g, a, b, c, d);
      if (!(tc != td)) return 0;
      int s1 = -1, s2 = -1;
      if (tc < td) {
        const int h1 = across(c, b, s1), h2 = across(d, a, s2);
        if (h1 < 0 || h2 < 0) return 0;
        splits.push_back({h1, c, b, d, f});
        splits.push_back({h2, d, a, c, g});
      } else {
        const int h1 = across(a, c, s1), h2 = across(b, d, s2);
        if (h1 < 0 || h2 < 0) return 0;
        splits.push_back({h1, a, c, d, f});
        splits.push_back({h2, b, d, c, g});
      }
      removed.push_back(g);
    }
    // The slots that change, their faces before, and the faces after.
    std::vector<int> slots;
    std::vector<Face> before, after, parent;
    std::vector<std::array<bool, 3>> flags_before;
    for (const Split& sp : splits) {
      if (std::find(removed.begin(), removed.end(), sp.h) != removed.end()) return 0;
      const Face& t = r_.faces[size_t(sp.h)];
      int k = 0;
      while (!(t[size_t(k)] == sp.p && t[size_t((k + 1) % 3)] == sp.q)) ++k;
      const int x = t[size_t((k + 2) % 3)];
      if (x == a || x == b || x == c || (double_cap && x == d)) return 0;
      slots.push_back(sp.h);
      after.push_back({sp.p, sp.s, x});
      slots.push_back(sp.free_slot);
      after.push_back({sp.s, sp.q, x});
      parent.push_back(t);
      parent.push_back(t);
    }
    for (int s : slots) {
      before.push_back(r_.faces[size_t(s)]);
      flags_before.push_back(r_.line_edge[size_t(s)]);
    }
    // Sides along a -> b: a line where any of them was.
    auto on_segment = [&](int u) { return u == a || u == b || u == c || (double_cap && u == d); };
    bool line = false;
    for (int s : removed)
      for (int k = 0; k < 3; ++k) line |= r_.line_edge[size_t(s)][size_t(k)];
    for (size_t i = 0; i < slots.size(); ++i) set_face(slots[i], after[i]);
    if (!fits(slots, after, parent, before)) {
      for (size_t i = 0; i < slots.size(); ++i) set_face(slots[i], before[i]);
      return 0;
    }
    // Flags: a split side keeps its parent's, the new inner sides have none, sides along
    // the segment get `line` on both of their faces.
    for (size_t i = 0; i < slots.size(); ++i) {
      const Face& t = after[i];
      const Face& p = parent[i];
      const auto& pf = flags_before[i & ~size_t(1)];  // the split face's own flags (its slot comes first)
      for (int k = 0; k < 3; ++k) {
        const int u = t[size_t(k)], w = t[size_t((k + 1) % 3)];
        bool flag = false;
        for (int m = 0; m < 3; ++m)
          if (p[size_t(m)] == u && p[size_t((m + 1) % 3)] == w) flag = pf[size_t(m)];
        r_.line_edge[size_t(slots[i])][size_t(k)] = flag;
      }
    }
    for (size_t i = 0; i < slots.size(); ++i) {
      const Face& t = after[i];
      for (int k = 0; k < 3; ++k) {
        const int u = t[size_t(k)], w = t[size_t((k + 1) % 3)];
        if (!on_segment(u) || !on_segment(w)) continue;
        r_.line_edge[size_t(slots[i])][size_t(k)] = line;
        int side = -1;
        const int o = across(w, u, side);
        if (o >= 0) r_.line_edge[size_t(o)][size_t(side)] = line;
      }
    }
    for (size_t i = 0; i < slots.size(); ++i) {
      const int s = slots[i], from = splits[i / 2].h;
      cut_[size_t(s)] = 1;
      if (!r_.face_source.empty()) r_.face_source[size_t(s)] = r_.face_source[size_t(from)];
      grid_->add(s);
    }
    return 1;
  }

  /// Caps f = (a, b, c) and g = (b, a, d) whose apexes rounded to one place or within
  /// tiny_ of it: their side flipped to (c, d), an edge without length or next to none,
  /// whose two faces (no area either) the merge of rounded edges then takes away with it
  /// (merge_rounded_together, run again, with its checks).
  int flip_to_apexes(int f, int g, int a, int b, int c, int d) {
    for (int h : vf_[size_t(c)])
      for (int v : r_.faces[size_t(h)])
        if (v == d) return 0;  // (c, d) is an edge already
    auto flag = [&](int face, int u, int w) {
      const Face& t = r_.faces[size_t(face)];
      for (int k = 0; k < 3; ++k)
        if (t[size_t(k)] == u && t[size_t((k + 1) % 3)] == w) return bool(r_.line_edge[size_t(face)][size_t(k)]);
      return false;
    };
    // All four sides lie along a -> b: a line where any side of the caps was.
    const bool line = flag(f, a, b) || flag(g, b, a) || flag(g, a, d) || flag(f, c, a) || flag(g, d, b) ||
                      flag(f, b, c);
    set_face(f, {a, d, c});
    set_face(g, {d, b, c});
    r_.line_edge[size_t(f)] = {line, false, line};
    r_.line_edge[size_t(g)] = {line, line, false};
    for (const auto& [u, w] : {std::pair{a, d}, std::pair{c, a}, std::pair{d, b}, std::pair{b, c}}) {
      int side = -1;
      const int o = across(w, u, side);
      if (o >= 0) r_.line_edge[size_t(o)][size_t(side)] = line;
    }
    cut_[size_t(f)] = cut_[size_t(g)] = 1;
    grid_->add(f);
    grid_->add(g);
    ++flipped_;
    return 1;
  }

  /// The new faces (in `slots`, already written) keep their parents' turn, add no directed
  /// side twice, and meet no face (nor each other) that the faces before did not meet.
  bool fits(const std::vector<int>& slots, const std::vector<Face>& after, const std::vector<Face>& parent,
            const std::vector<Face>& before) {
    auto corners = [&](const Face& t, V3 q[3]) {
      for (int z = 0; z < 3; ++z) q[z] = at(t[size_t(z)]);
    };
    for (size_t i = 0; i < after.size(); ++i) {
      V3 q[3], p[3];
      corners(after[i], q);
      corners(parent[i], p);
      const int k = largest_normal_axis(p), u = (k + 1) % 3, w = (k + 2) % 3;
      const int turn = orient2d(p[0].data(), p[1].data(), p[2].data(), u, w);
      if (turn == 0 || orient2d(q[0].data(), q[1].data(), q[2].data(), u, w) != turn) return false;
    }
    // Every directed side of a new face once in the surface, its reverse once.
    for (const Face& t : after)
      for (int k = 0; k < 3; ++k) {
        const int u = t[size_t(k)], w = t[size_t((k + 1) % 3)];
        int forward = 0, backward = 0;
        for (int h : vf_[size_t(u)]) {
          const Face& o = r_.faces[size_t(h)];
          for (int m = 0; m < 3; ++m) {
            forward += o[size_t(m)] == u && o[size_t((m + 1) % 3)] == w;
            backward += o[size_t(m)] == w && o[size_t((m + 1) % 3)] == u;
          }
        }
        if (forward != 1 || backward != 1) return false;
      }
    auto met_before = [&](const Face& g) {
      V3 gq[3], oq[3];
      corners(g, gq);
      for (const Face& o : before) {
        corners(o, oq);
        if (triangles_meet(o, oq, g, gq)) return true;
      }
      return false;
    };
    for (size_t i = 0; i < after.size(); ++i) {
      V3 q[3];
      corners(after[i], q);
      V3 lo = q[0], hi = q[0];
      for (int z = 1; z < 3; ++z)
        for (int m = 0; m < 3; ++m) { lo[m] = std::min(lo[m], q[z][m]); hi[m] = std::max(hi[m], q[z][m]); }
      grid_->near(lo, hi, near_);
      for (int g : near_) {
        if (std::find(slots.begin(), slots.end(), g) != slots.end()) continue;
        const Face& u = r_.faces[size_t(g)];
        V3 gq[3];
        corners(u, gq);
        if (triangles_meet(after[i], q, u, gq) && !met_before(u)) return false;
      }
      // Halves of one face meet along their new side only; halves of the two sheets'
      // faces (two caps) where those faces met already.
      for (size_t j = 0; j < i; ++j) {
        V3 gq[3], pi[3], pj[3];
        corners(after[j], gq);
        if (!triangles_meet(after[i], q, after[j], gq)) continue;
        corners(parent[i], pi);
        corners(parent[j], pj);
        if (parent[i] == parent[j] || !triangles_meet(parent[i], pi, parent[j], pj)) return false;
      }
    }
    return true;
  }

  Result& r_;
  std::vector<char>& cut_;
  double tiny_;
  std::vector<std::vector<int>> vf_;
  std::optional<FaceGrid> grid_;  // face boxes as filed before the first change, refiled after each
  std::vector<int> near_;

public:
  int flipped_ = 0;  // cap pairs left to merge_rounded_together
};

}  // namespace

int split_rounded_caps(Result& r, std::vector<char>& cut, int* flipped) {
  CapSplitter splitter(r, cut);
  const int n = splitter.run();
  if (flipped) *flipped = splitter.flipped_;
  return n;
}

}  // namespace mr::surface_union
