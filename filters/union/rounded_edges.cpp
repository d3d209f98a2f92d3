#include "union/rounded_edges.h"

#include <algorithm>

namespace mr::surface_union {

namespace {

class EdgeMerger {
public:
  EdgeMerger(Result& r, std::vector<char>& cut) : r_(r), cut_(cut) {}

  int run() {
    // A zero-length edge has a crossing at one end at least, so its faces are cut faces.
    // Most unions have none: the stars are built only then.
    if (!any_zero_length_edge()) return 0;
    alive_.assign(r_.faces.size(), 1);
    vf_.assign(r_.vertices.size(), {});
    for (int f = 0; f < int(r_.faces.size()); ++f)
      for (int v : r_.faces[size_t(f)]) vf_[size_t(v)].push_back(f);
    int merged = 0;
    for (bool again = true; again;) {
      again = false;
      for (int f = 0; f < int(r_.faces.size()); ++f)
        for (int z = 0; z < 3 && alive_[size_t(f)] && cut_[size_t(f)]; ++z) {
          const int u = r_.faces[size_t(f)][size_t(z)], w = r_.faces[size_t(f)][size_t((z + 1) % 3)];
          if (u != w && r_.vertices[size_t(u)] == r_.vertices[size_t(w)] && merge(std::min(u, w), std::max(u, w))) {
            ++merged;
            again = true;
          }
        }
    }
    if (merged > 0) compact();
    return merged;
  }

private:
  bool any_zero_length_edge() const {
    for (size_t f = 0; f < r_.faces.size(); ++f)
      if (cut_[f])
        for (int z = 0; z < 3; ++z)
          if (r_.vertices[size_t(r_.faces[f][size_t(z)])] == r_.vertices[size_t(r_.faces[f][size_t((z + 1) % 3)])])
            return true;
    return false;
  }
  bool has(int f, int v) const {
    const auto& t = r_.faces[size_t(f)];
    return t[0] == v || t[1] == v || t[2] == v;
  }
  void live(int v, std::vector<int>& out) const {
    out.clear();
    for (int f : vf_[size_t(v)])
      if (alive_[size_t(f)]) out.push_back(f);
  }
  /// The side of face f from a to b (either way round), or -1.
  int side(int f, int a, int b) const {
    const auto& t = r_.faces[size_t(f)];
    for (int z = 0; z < 3; ++z) {
      const int x = t[size_t(z)], y = t[size_t((z + 1) % 3)];
      if ((x == a && y == b) || (x == b && y == a)) return z;
    }
    return -1;
  }
  /// The live face other than `not_f` with side (a, b), or -1.
  int across(int a, int b, int not_f) const {
    for (int g : vf_[size_t(a)])
      if (alive_[size_t(g)] && g != not_f && has(g, b)) return g;
    return -1;
  }

  bool merge(int keep, int gone) {
    live(keep, fk_);
    live(gone, fg_);
    both_.clear();
    for (int f : fg_)
      if (has(f, keep)) both_.push_back(f);
    if (both_.size() != 2) return false;
    // Link condition: the ends' rings share only the two corners opposite the edge.
    ring_.clear();
    for (int f : fk_)
      for (int x : r_.faces[size_t(f)])
        if (x != keep && x != gone) ring_.push_back(x);
    std::sort(ring_.begin(), ring_.end());
    ring_.erase(std::unique(ring_.begin(), ring_.end()), ring_.end());
    common_.clear();
    for (int f : fg_)
      for (int x : r_.faces[size_t(f)])
        if (x != keep && x != gone && std::binary_search(ring_.begin(), ring_.end(), x)) common_.push_back(x);
    std::sort(common_.begin(), common_.end());
    common_.erase(std::unique(common_.begin(), common_.end()), common_.end());
    if (common_.size() != 2) return false;
    // Where a dying face (keep, gone, x) leaves, the faces across its sides (gone, x)
    // and (x, keep) become neighbours along (keep, x): one line edge if either was.
    struct Join {
      int g1, z1, g2, z2;
    };
    Join joins[2];
    for (int k = 0; k < 2; ++k) {
      const int d = both_[size_t(k)];
      int x = -1;
      for (int y : r_.faces[size_t(d)])
        if (y != keep && y != gone) x = y;
      const int g1 = across(gone, x, d), g2 = across(keep, x, d);
      if (g1 < 0 || g2 < 0) return false;  // an open side: not the closed surface assumed
      joins[k] = {g1, side(g1, gone, x), g2, side(g2, keep, x)};
    }
    for (int d : both_) alive_[size_t(d)] = 0;
    for (int f : fg_) {
      if (!alive_[size_t(f)]) continue;
      for (int& x : r_.faces[size_t(f)])
        if (x == gone) x = keep;
      vf_[size_t(keep)].push_back(f);
    }
    vf_[size_t(gone)].clear();
    for (const Join& j : joins) {
      bool& a = r_.line_edge[size_t(j.g1)][size_t(j.z1)];
      bool& b = r_.line_edge[size_t(j.g2)][size_t(j.z2)];
      a = b = a || b;
    }
    return true;
  }

  void compact() {
    std::vector<int> index(r_.vertices.size(), -1);
    std::vector<std::array<double, 3>> vertices;
    size_t k = 0;
    for (size_t f = 0; f < r_.faces.size(); ++f) {
      if (!alive_[f]) continue;
      for (int& v : r_.faces[f]) {
        if (index[size_t(v)] < 0) {
          index[size_t(v)] = int(vertices.size());
          vertices.push_back(r_.vertices[size_t(v)]);
        }
        v = index[size_t(v)];
      }
      r_.faces[k] = r_.faces[f];
      r_.line_edge[k] = r_.line_edge[f];
      cut_[k] = cut_[f];
      ++k;
    }
    r_.faces.resize(k);
    r_.line_edge.resize(k);
    cut_.resize(k);
    r_.vertices = std::move(vertices);
  }

  Result& r_;
  std::vector<char>& cut_;
  std::vector<char> alive_;
  std::vector<std::vector<int>> vf_;
  std::vector<int> fk_, fg_, both_, ring_, common_;
};

}  // namespace

int merge_zero_length_edges(Result& r, std::vector<char>& cut) { return EdgeMerger(r, cut).run(); }

}  // namespace mr::surface_union
