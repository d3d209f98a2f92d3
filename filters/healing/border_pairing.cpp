#include "healing/border_pairing.h"

#include "common/uniform_grid.h"
#include "healing/border_grid.h"
#include "common/segment_geometry.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <tuple>

namespace mr::healing {
namespace {

// A cluster larger than this is a sign the tolerance is far too big for the
// mesh; refusing to grow it keeps the pairwise checks cheap.
constexpr size_t kMaxCluster = 16;

/// True if a and b share an edge.
bool adjacent(const EdgeTable& edges, int a, int b) { return edges.find(a, b) >= 0; }

/// Largest distance from samples of one segment to the other, both ways:
/// the discrete Hausdorff distance the paper uses to verify a pairing.
double segment_hausdorff(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  double worst = 0;
  for (int k = 0; k <= 4; ++k) {
    const double t = k / 4.0;
    worst = std::max(worst, point_segment_distance(a + (b - a) * t, c, d));
    worst = std::max(worst, point_segment_distance(c + (d - c) * t, a, b));
  }
  return worst;
}

/// Candidate clusters of border vertices: greedy merging of the closest pairs,
/// keeping every cluster within `tol` in diameter and free of mesh edges.
class Clusters {
public:
  Clusters(const Soup& s, const EdgeTable& nb, double tol)
      : s_(s), nb_(nb), tol_(tol), id_(s.pos.size()), members_(s.pos.size()) {
    for (size_t v = 0; v < id_.size(); ++v) { id_[v] = int(v); members_[v] = {int(v)}; }
  }
  int id(int v) const { return id_[v]; }
  const std::vector<int>& members(int v) const { return members_[id_[v]]; }

  bool can_join(int v, const Point3& p, int cluster_of) const {
    for (int m : members_[id_[cluster_of]])
      if (vcg::Distance(s_.pos[m], p) > tol_ || (v >= 0 && adjacent(nb_, m, v))) return false;
    return members_[id_[cluster_of]].size() < kMaxCluster;
  }

  bool merge(int u, int v) {
    int a = id_[u], b = id_[v];
    if (a == b) return false;
    if (members_[a].size() + members_[b].size() > kMaxCluster) return false;
    for (int x : members_[a])
      for (int y : members_[b])
        if (vcg::Distance(s_.pos[x], s_.pos[y]) > tol_ || adjacent(nb_, x, y)) return false;
    if (b < a) std::swap(a, b);
    for (int y : members_[b]) { id_[y] = a; members_[a].push_back(y); }
    members_[b].clear();
    return true;
  }

  /// Adds vertex `v` (new, no neighbours yet in `nb_`) to the cluster of `of`.
  void add(int v, int of) {
    const int a = id_[of];
    if (int(id_.size()) <= v) { id_.resize(v + 1); members_.resize(v + 1); }
    id_[v] = a;
    members_[a].push_back(v);
  }
  void add_singleton(int v) {
    if (int(id_.size()) <= v) { id_.resize(v + 1); members_.resize(v + 1); }
    id_[v] = v;
    members_[v] = {v};
  }

private:
  const Soup& s_;
  const EdgeTable& nb_;
  double tol_;
  std::vector<int> id_;
  std::vector<std::vector<int>> members_;
};

uint64_t edge_key(int a, int b) {
  return (uint64_t(std::min(a, b)) << 32) | uint32_t(std::max(a, b));
}

struct Split {
  int edge;      ///< index into the border list
  double t;      ///< parameter along v0 -> v1 of that edge
  int vertex;    ///< the T-vertex
};

/// Step 2: splits border edges at border vertices of other edges that lie within
/// `tol` of their interior. Returns the number of splits.
int split_t_junctions(Soup& s, const EdgeTable& edges, const std::vector<int>& border,
                      const std::vector<char>& is_border_vertex, Clusters& clusters, double tol) {
  UniformGrid grid(border_grid_cell(s, edges, border, tol));
  for (size_t i = 0; i < border.size(); ++i) {
    grid.insert_segment(int(i), s.pos[edges.v0(border[i])], s.pos[edges.v1(border[i])], tol);
  }

  std::vector<Split> splits;
  for (int v = 0; v < int(is_border_vertex.size()); ++v) {
    if (!is_border_vertex[v]) continue;
    const Point3& p = s.pos[v];
    int best = -1;
    double best_d = tol, best_t = 0;
    grid.visit(p, 0, [&](int i) {
      const auto e = edges.ends(border[i]);
      if (e.v0 == v || e.v1 == v) return;
      const auto& face = s.tri[edges.side(border[i], 0).face];
      if (face[0] == v || face[1] == v || face[2] == v) return;
      if (clusters.id(v) == clusters.id(e.v0) || clusters.id(v) == clusters.id(e.v1)) return;
      const Point3 &a = s.pos[e.v0], &b = s.pos[e.v1];
      if (vcg::Distance(p, a) <= tol || vcg::Distance(p, b) <= tol) return;
      const double t = segment_param(p, a, b);
      if (t <= 0 || t >= 1) return;
      const double d = vcg::Distance(p, a + (b - a) * t);
      if (d < best_d || (d == best_d && best >= 0 && i < best)) { best = i; best_d = d; best_t = t; }
    });
    if (best >= 0 && clusters.can_join(-1, s.pos[edges.v0(border[best])] * (1 - best_t) +
                                                s.pos[edges.v1(border[best])] * best_t, v))
      splits.push_back({best, best_t, v});
  }
  std::sort(splits.begin(), splits.end(), [](const Split& x, const Split& y) {
    return std::tie(x.edge, x.t, x.vertex) < std::tie(y.edge, y.t, y.vertex);
  });

  // Which face currently holds each border edge (faces change as they split).
  std::map<uint64_t, int> holder;
  for (int e : border) holder[edge_key(edges.v0(e), edges.v1(e))] = edges.side(e, 0).face;

  int count = 0;
  for (size_t i = 0; i < splits.size();) {
    size_t j = i;
    while (j < splits.size() && splits[j].edge == splits[i].edge) ++j;
    const auto e = edges.ends(border[splits[i].edge]);
    // One new vertex per T-vertex cluster along this edge.
    std::vector<std::pair<double, int>> cuts;
    for (size_t k = i; k < j; ++k) {
      bool seen = false;
      for (const auto& c : cuts) seen |= clusters.id(c.second) == clusters.id(splits[k].vertex);
      if (!seen) cuts.push_back({splits[k].t, splits[k].vertex});
    }
    i = j;
    const int f = holder[edge_key(e.v0, e.v1)];
    auto& t = s.tri[f];
    int z = 0;
    while (!((t[z] == e.v0 && t[(z + 1) % 3] == e.v1) || (t[z] == e.v1 && t[(z + 1) % 3] == e.v0))) ++z;
    const int a = t[z], b = t[(z + 1) % 3], c = t[(z + 2) % 3];
    if (a != e.v0) {  // the face runs v1 -> v0: cut in that order
      std::reverse(cuts.begin(), cuts.end());
      for (auto& cut : cuts) cut.first = 1 - cut.first;
    }
    std::vector<int> chain = {a};
    for (const auto& cut : cuts) {
      const int nv = int(s.pos.size());
      s.pos.push_back(s.pos[a] * (1 - cut.first) + s.pos[b] * cut.first);
      clusters.add(nv, cut.second);
      chain.push_back(nv);
      ++count;
    }
    chain.push_back(b);
    const int patch = s.patch[f];
    s.tri[f] = {chain[0], chain[1], c};
    for (size_t k = 1; k + 1 < chain.size(); ++k) {
      s.tri.push_back({chain[k], chain[k + 1], c});
      s.patch.push_back(patch);
    }
    // The side b-c now belongs to the last face of the fan.
    auto it = holder.find(edge_key(b, c));
    if (it != holder.end() && chain.size() > 2) it->second = int(s.tri.size()) - 1;
  }
  return count;
}

/// Weld classes of the accepted pairs. A pair that, through the classes it
/// joins, would collapse a face or put three faces on one edge (a triple seam,
/// a fold of the border onto itself) is dropped, and the classes rebuilt.
template <class Pairs>
std::vector<int> weld_without_defects(const Soup& s, const EdgeTable& edges, const Clusters& clusters,
                                      Pairs pairs, std::vector<std::array<int, 2>>& seam_edges) {
  const int n = int(s.pos.size());
  std::vector<int> cls(n);
  for (int round = 0; round < 20; ++round) {
    UnionFind weld(n);
    for (const auto& p : pairs) {
      const auto e = edges.ends(p.e), g = edges.ends(p.g);
      if (clusters.id(e.v0) == clusters.id(g.v0)) { weld.unite(e.v0, g.v0); weld.unite(e.v1, g.v1); }
      else { weld.unite(e.v0, g.v1); weld.unite(e.v1, g.v0); }
    }
    std::vector<char> welded(n, 0);
    for (int v = 0; v < n; ++v) { cls[v] = weld.find(v); if (cls[v] != v) welded[v] = welded[cls[v]] = 1; }
    // Faces per welded edge; only faces touching a welded vertex can change.
    std::vector<std::pair<uint64_t, int>> welded_sides;
    for (size_t f = 0; f < s.tri.size(); ++f) {
      if (!(welded[s.tri[f][0]] || welded[s.tri[f][1]] || welded[s.tri[f][2]])) continue;
      for (int z = 0; z < 3; ++z)
        welded_sides.push_back({edge_key(cls[s.tri[f][z]], cls[s.tri[f][(z + 1) % 3]]), int(f)});
    }
    std::sort(welded_sides.begin(), welded_sides.end());
    std::vector<char> bad_vertex(n, 0);
    for (size_t i = 0; i < welded_sides.size();) {
      size_t j = i;
      while (j < welded_sides.size() && welded_sides[j].first == welded_sides[i].first) ++j;
      const uint64_t k = welded_sides[i].first;
      const bool collapsed = (k >> 32) == (k & 0xffffffffu);
      if (collapsed || j - i > 2)
        for (size_t x = i; x < j; ++x)
          for (int v : s.tri[welded_sides[x].second]) bad_vertex[v] = 1;
      i = j;
    }
    Pairs kept;
    for (const auto& p : pairs) {
      const auto e = edges.ends(p.e), g = edges.ends(p.g);
      if (!(bad_vertex[e.v0] || bad_vertex[e.v1] || bad_vertex[g.v0] || bad_vertex[g.v1])) kept.push_back(p);
    }
    if (kept.size() == pairs.size()) break;
    pairs.swap(kept);
  }
  seam_edges.clear();
  for (const auto& p : pairs) seam_edges.push_back({edges.v0(p.e), edges.v1(p.e)});
  return cls;
}

}  // namespace

Pairing pair_borders(Soup& s, double vtol, double etol) {
  Pairing out;
  auto edges = soup_edges(s);
  std::vector<int> border;
  std::vector<char> is_border_vertex(s.pos.size(), 0);
  for (int e = 0; e < edges.edge_count(); ++e)
    if (edges.valence(e) == 1) {
      border.push_back(int(e));
      is_border_vertex[edges.v0(e)] = is_border_vertex[edges.v1(e)] = 1;
    }
  out.border_edges = int(border.size());

  // Step 1: candidate clusters from border vertex pairs, closest first.
  Clusters clusters(s, edges, vtol);
  {
    UniformGrid grid(vtol);
    for (int v = 0; v < int(s.pos.size()); ++v)
      if (is_border_vertex[v]) grid.insert(v, s.pos[v]);
    std::vector<std::tuple<double, int, int>> close;
    for (int u = 0; u < int(s.pos.size()); ++u) {
      if (!is_border_vertex[u]) continue;
      grid.visit(s.pos[u], vtol, [&](int v) {
        if (v <= u) return;
        const double d = vcg::Distance(s.pos[u], s.pos[v]);
        if (d <= vtol && !adjacent(edges, u, v)) close.emplace_back(d, u, v);
      });
    }
    std::sort(close.begin(), close.end());
    for (const auto& [d, u, v] : close) clusters.merge(u, v);
  }

  // Step 2: T-junctions.
  out.t_junctions = split_t_junctions(s, edges, border, is_border_vertex, clusters, vtol);

  // Step 3: border edges whose ends lie in the same two clusters pair up, if
  // the edges themselves are within the edge tolerance.
  edges = soup_edges(s);
  std::vector<std::pair<uint64_t, int>> keyed;
  for (int e = 0; e < edges.edge_count(); ++e) {
    if (edges.valence(e) != 1) continue;
    const int ca = clusters.id(edges.v0(e)), cb = clusters.id(edges.v1(e));
    if (ca != cb) keyed.push_back({edge_key(ca, cb), int(e)});
  }
  std::sort(keyed.begin(), keyed.end());
  struct Pair { int e, g; };
  std::vector<Pair> pairs;
  for (size_t i = 0; i < keyed.size();) {
    size_t j = i;
    while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
    std::vector<std::tuple<double, int, int>> options;
    for (size_t x = i; x < j; ++x)
      for (size_t y = x + 1; y < j; ++y) {
        const auto e = edges.ends(keyed[x].second), g = edges.ends(keyed[y].second);
        options.emplace_back(segment_hausdorff(s.pos[e.v0], s.pos[e.v1], s.pos[g.v0], s.pos[g.v1]),
                             keyed[x].second, keyed[y].second);
      }
    std::sort(options.begin(), options.end());
    std::vector<int> used;
    bool any_rejected = false;
    for (const auto& [d, x, y] : options) {
      if (std::count(used.begin(), used.end(), x) || std::count(used.begin(), used.end(), y)) continue;
      if (d > etol) { any_rejected = true; continue; }
      used.push_back(x);
      used.push_back(y);
      pairs.push_back({x, y});
    }
    if (any_rejected && used.empty()) ++out.rejected;
    i = j;
  }
  out.weld_class = weld_without_defects(s, edges, clusters, pairs, out.seam_edges);
  out.pairs = int(out.seam_edges.size());
  return out;
}

}  // namespace mr::healing
