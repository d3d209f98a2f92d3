#include "remesh/wedge_relaxing.h"

#include "remesh/mesh_measures.h"
#include "remesh/point_stars.h"
#include "remesh/triangle_geometry.h"
#include "remesh/wedge_tips.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <unordered_set>

namespace mr::remesh {

namespace {

// New faces may not turn by more than acos(0.7) from the faces they replace (as for line points).
constexpr double kFoldCos = 0.7;

// A point's place on a path: (path, index).
using Place = std::pair<int, int>;

class WedgeRelaxing {
public:
  WedgeRelaxing(OutputMesh& out, std::vector<LinePath>& paths, const std::vector<std::array<int, 2>>& feature_edges,
                const SurfaceLocator& locator, const SizeField& size)
      : out_(out), paths_(paths), locator_(locator), size_(size), stars_(out),
        feature_(OutputMesh::edge_key_set(feature_edges)), places_(out.points.size()) {
    for (int a = 0; a < int(paths_.size()); ++a)
      for (int i = 0; i < int(paths_[a].points.size()); ++i) places_[size_t(paths_[a].points[i])].push_back({a, i});
  }

  /// One sweep over the faces, in order: wedge tips.
  void run() {
    for (size_t k = 0; k < out_.faces.size(); ++k)
      for (int z = 0; z < 3; ++z) {
        const auto& t = out_.faces[k];
        if (t[0] < 0) break;  // merged away this sweep
        if (try_relax(int(k), t[z], t[(z + 1) % 3], t[(z + 2) % 3])) break;
      }
  }

  /// One sweep over the faces, in order: lines that pass close, where a face is under `below`.
  void close_gaps(double below) {
    below_ = below;
    for (size_t k = 0; k < out_.faces.size(); ++k)
      for (int z = 0; z < 3; ++z) {
        const auto& t = out_.faces[k];
        if (t[0] < 0) break;
        if (try_close(int(k), t[z], t[(z + 1) % 3]) || try_snap(int(k), t[z], t[(z + 1) % 3], t[(z + 2) % 3])) break;
      }
  }

  std::vector<int> finish(std::vector<std::array<int, 2>>& feature_edges) {
    auto final_point = [&](int x) {
      for (auto it = merged_into_.find(x); it != merged_into_.end(); it = merged_into_.find(x)) x = it->second;
      return x;
    };
    if (merged_.empty()) return {};
    // A snapped segment runs through its point (in the order of the snaps: a later one may
    // split a piece of an earlier one).
    std::map<std::uint64_t, int> split_at;
    for (const auto& [a, b, q] : snaps_) split_at[OutputMesh::edge_key(final_point(a), final_point(b))] = final_point(q);
    // The second line's first segment becomes the first line's: listed once.
    std::vector<std::array<int, 2>> edges;
    std::unordered_set<std::uint64_t> seen;
    std::vector<std::array<int, 2>> pieces;
    for (const auto& e : feature_edges) {
      pieces.assign(1, {final_point(e[0]), final_point(e[1])});
      while (!pieces.empty()) {
        const auto [a, b] = pieces.back();
        pieces.pop_back();
        if (a == b) continue;
        const auto it = split_at.find(OutputMesh::edge_key(a, b));
        if (it != split_at.end() && it->second != a && it->second != b) {
          pieces.push_back({it->second, b});
          pieces.push_back({a, it->second});
        } else if (seen.insert(OutputMesh::edge_key(a, b)).second) {
          edges.push_back({a, b});
        }
      }
    }
    feature_edges = std::move(edges);
    drop_dead_faces(out_);
    return merged_;
  }

private:
  OutputMesh& out_;
  std::vector<LinePath>& paths_;
  const SurfaceLocator& locator_;
  const SizeField& size_;
  PointStars stars_;
  std::unordered_set<std::uint64_t> feature_;
  std::vector<std::vector<Place>> places_;  // per point: where paths hold it
  std::map<int, int> merged_into_;
  std::vector<int> merged_;
  std::vector<std::array<int, 3>> snaps_;  // (a, b, q): line segment a-b now runs through q
  double below_ = 1e9;  // a merge or snap must lift a smallest angle under this

  bool is_feature(int a, int b) const { return feature_.count(OutputMesh::edge_key(a, b)) > 0; }

  // The place of p next to tip c on some path other than `not_path` (-1: any): p slidable there,
  // or a corner (the end of that path and of others).
  bool beside(int c, int p, int not_path, Place& where) const {
    const std::vector<Place>& held = places_[size_t(p)];
    // A junction is merged as a corner would be (neither slides).
    const bool fixed = out_.kind[size_t(p)] == PointKind::Corner || junction(p);
    for (const auto& [a, i] : held) {
      if (a == not_path || !(fixed || paths_[size_t(a)].slidable[size_t(i)])) continue;
      const auto& pts = paths_[size_t(a)].points;
      if ((i > 0 && pts[size_t(i) - 1] == c) || (i + 1 < int(pts.size()) && pts[size_t(i) + 1] == c)) {
        where = {a, i};
        return true;
      }
    }
    return false;
  }

  // p is no corner but several paths hold it (lines that share a stretch part there, as an
  // earlier merge leaves them).
  bool junction(int p) const { return out_.kind[size_t(p)] != PointKind::Corner && places_[size_t(p)].size() > 1; }

  // Some path holds both p and q: merged, it would run from the point back to itself.
  bool on_one_path(int p, int q) const {
    for (const Place& x : places_[size_t(p)])
      for (const Place& y : places_[size_t(q)])
        if (x.first == y.first) return true;
    return false;
  }

  // Smallest angle of v's faces but `skip` once v and `other` are one point at `at`; `folds`
  // when one of them turns too far.
  double star_min_angle(int v, const std::vector<int>& skip, const Point3& at, int other, bool& folds) const {
    double worst = 1e9;
    for (int k : stars_.of(v)) {
      if (std::find(skip.begin(), skip.end(), k) != skip.end()) continue;
      const auto& t = out_.faces[size_t(k)];
      std::array<Point3, 3> q;
      for (int z = 0; z < 3; ++z) q[size_t(z)] = t[size_t(z)] == v || t[size_t(z)] == other ? at : out_.points[size_t(t[size_t(z)])];
      const Point3 n_old = unit_normal(out_.points[t[0]], out_.points[t[1]], out_.points[t[2]]);
      if (unit_normal(q[0], q[1], q[2]) * n_old < kFoldCos) folds = true;
      worst = std::min(worst, min_angle(q[0], q[1], q[2]));
    }
    return worst;
  }

  // Face k's corner c between its sides to p1 and p2.
  bool try_relax(int k, int c, int p1, int p2) {
    if (!is_feature(c, p1) || !is_feature(c, p2) || is_feature(p1, p2)) return false;
    if (!(corner_angle(out_.points[c], out_.points[p1], out_.points[p2]) < kWedgeBoundRad)) return false;
    Place a, b;
    if (!beside(c, p1, -1, a) || !beside(c, p2, a.first, b) || on_one_path(p1, p2)) return false;
    const double width = (out_.points[p1] - out_.points[p2]).Norm();
    if (!(width <= kRelaxWidth * size_at_point(out_, locator_, size_, c))) return false;
    return merge(k, p1, p2, width);
  }

  // Face k's side p1 -> p2 joins points of two lines that pass closer than kCloseGap x the size
  // without meeting there (circles of a sphere cluster 0.0003 apart): the strip between them
  // holds only slivers. The two points merge as beside a wedge tip; the lines then meet there,
  // and the wedges this leaves on either side are relaxed in the next sweeps.
  bool try_close(int k, int p1, int p2) {
    if (places_[size_t(p1)].empty() || places_[size_t(p2)].empty() || is_feature(p1, p2) || on_one_path(p1, p2))
      return false;
    // Every edge between two line points comes here: the size lookups (a closest point each) last.
    const double width = (out_.points[p1] - out_.points[p2]).Norm();
    if (!(width <= kCloseGap * size_.max_size()) || !may_merge(p1) || !may_merge(p2)) return false;
    const double h = std::min(size_at_point(out_, locator_, size_, p1), size_at_point(out_, locator_, size_, p2));
    if (!(width <= kCloseGap * h)) return false;
    return merge(k, p1, p2, width);
  }

  // p may merge where every path through it lets it slide, or it is fixed (as in beside()).
  bool may_merge(int p) const {
    if (out_.kind[size_t(p)] == PointKind::Corner || junction(p)) return true;
    for (const auto& [a, i] : places_[size_t(p)])
      if (!paths_[size_t(a)].slidable[size_t(i)]) return false;
    return true;
  }

  // Face k = (a, b, q), its side a -> b a line segment, q a point of another line closer than
  // kCloseGap x the size to that segment's middle part (a cap: lines 0.0002 apart, the apex of
  // one facing the middle of the other's segment). The segment flips to q-x (x across it) and
  // the line runs a-q-b: the cap goes, and q joins both lines, where it is or on the way to the
  // segment.
  bool try_snap(int k, int a, int b, int q) {
    if (!is_feature(a, b) || places_[size_t(q)].empty() || !may_merge(q)) return false;
    const Point3 ab = out_.points[b] - out_.points[a];
    const double t = ((out_.points[q] - out_.points[a]) * ab) / (ab * ab);
    if (!(t > kSnapFrom && t < 1 - kSnapFrom)) return false;
    const Point3 foot = out_.points[a] + ab * t;
    const double gap = (out_.points[q] - foot).Norm();
    if (!(gap <= kCloseGap * size_.max_size())) return false;
    const double h = std::min({size_at_point(out_, locator_, size_, a), size_at_point(out_, locator_, size_, b),
                               size_at_point(out_, locator_, size_, q)});
    if (!(gap <= kCloseGap * h)) return false;
    // The paths that run a-b (q on none of them), and the face across the segment.
    std::vector<Place> runs;
    for (const auto& [path, i] : places_[size_t(a)]) {
      const auto& pts = paths_[size_t(path)].points;
      const bool beside_b = (i + 1 < int(pts.size()) && pts[size_t(i) + 1] == b) || (i > 0 && pts[size_t(i) - 1] == b);
      // (Once a path: a closed path holds its first point twice.)
      if (beside_b && std::none_of(runs.begin(), runs.end(), [&, p = path](const Place& r) { return r.first == p; }))
        runs.push_back({path, i});
    }
    if (runs.empty()) return false;
    for (const Place& r : runs)
      for (const Place& x : places_[size_t(q)])
        if (x.first == r.first) return false;
    const std::vector<int> on_ab = stars_.faces_on(out_, a, b);
    if (on_ab.size() != 2) return false;
    const int g = on_ab[0] == k ? on_ab[1] : on_ab[0];
    int x = -1;
    for (int v : out_.faces[size_t(g)])
      if (v != a && v != b) x = v;
    if (x < 0 || x == q) return false;
    for (int f : stars_.of(q))
      for (int v : out_.faces[size_t(f)])
        if (v == x) return false;  // q-x is an edge already
    // The cap's side a -> b: after the flip (a, x, q) and (x, b, q), both on g's patch.
    const std::array<int, 3> nk{a, x, q}, ng{x, b, q};
    double before = min_angle(out_.points, out_.faces[size_t(g)]);
    for (int f : stars_.of(q)) before = std::min(before, min_angle(out_.points, out_.faces[size_t(f)]));
    if (!(before < below_)) return false;
    std::vector<std::pair<Point3, int>> places;
    if (!junction(q) && out_.kind[size_t(q)] != PointKind::Corner) {
      for (const Point3& at : {(out_.points[q] + foot) * 0.5, foot}) {
        const Projection pr = locator_.locate(at, out_.face_patch[size_t(k)], Point3(0, 0, 0), out_.host[q], gap);
        if (pr.face >= 0) places.push_back({pr.point, pr.face});
      }
    }
    places.push_back({out_.points[q], out_.host[q]});
    const Point3 n_g = unit_normal(out_.points[out_.faces[g][0]], out_.points[out_.faces[g][1]], out_.points[out_.faces[g][2]]);
    int chosen = -1;
    for (int n = 0; n < int(places.size()) && chosen < 0; ++n) {
      const Point3& at = places[size_t(n)].first;
      auto corner = [&](int v) { return v == q ? at : out_.points[size_t(v)]; };
      bool folds = false;
      double after = 1e9;
      for (const auto& t : {nk, ng}) {
        const Point3 p0 = corner(t[0]), p1 = corner(t[1]), p2 = corner(t[2]);
        if (unit_normal(p0, p1, p2) * n_g < kFoldCos) folds = true;
        after = std::min(after, min_angle(p0, p1, p2));
      }
      after = std::min(after, star_min_angle(q, {k}, at, q, folds));  // q's other faces, q moved
      if (!folds && after > before + 1e-9) chosen = n;
    }
    if (chosen < 0) return false;
    out_.points[q] = places[size_t(chosen)].first;
    out_.host[q] = places[size_t(chosen)].second;
    flip(k, g, a, b, q, x, nk, ng);
    feature_.erase(OutputMesh::edge_key(a, b));
    feature_.insert(OutputMesh::edge_key(a, q));
    feature_.insert(OutputMesh::edge_key(q, b));
    for (const Place& r : runs) insert_into_path(r, b, q);
    for (const Place& x2 : places_[size_t(q)]) paths_[size_t(x2.first)].slidable[size_t(x2.second)] = 0;
    snaps_.push_back({a, b, q});
    merged_.push_back(q);
    return true;
  }

  // Faces k = (a, b, q) and g = (b, a, x) become (a, x, q) and (x, b, q), both on g's patch.
  void flip(int k, int g, int a, int b, int q, int x, const std::array<int, 3>& nk, const std::array<int, 3>& ng) {
    out_.faces[size_t(k)] = nk;
    out_.faces[size_t(g)] = ng;
    out_.face_patch[size_t(k)] = out_.face_patch[size_t(g)];
    stars_.drop_face(a, g);
    stars_.drop_face(b, k);
    stars_.of(x).push_back(k);
    stars_.of(q).push_back(g);
  }

  // Path r.first holds a at r.second and b beside it: q goes between them.
  void insert_into_path(const Place& r, int b, int q) {
    LinePath& path = paths_[size_t(r.first)];
    const int i = r.second;
    const int at = i + 1 < int(path.points.size()) && path.points[size_t(i) + 1] == b ? i + 1 : i;  // index of the later one
    const double arc = 0.5 * (path.arc[size_t(at) - 1] + path.arc[size_t(at)]);
    for (size_t j = size_t(at); j < path.points.size(); ++j)
      for (Place& pl : places_[size_t(path.points[j])])
        if (pl.first == r.first && pl.second == int(j)) ++pl.second;
    path.points.insert(path.points.begin() + at, q);
    path.arc.insert(path.arc.begin() + at, arc);
    path.slidable.insert(path.slidable.begin() + at, 0);
    places_[size_t(q)].push_back({r.first, at});
  }

  // p2 into p1 (face k is one of the two faces on their side), where the link condition holds.
  bool merge(int k, int p1, int p2, double width) {
    const std::vector<int> dying = stars_.faces_on(out_, p2, p1);
    if (dying.size() != 2 || !stars_.link_condition(out_, p2, p1, dying)) return false;
    double before = 1e9;
    for (int v : {p1, p2})
      for (int f : stars_.of(v)) before = std::min(before, min_angle(out_.points, out_.faces[size_t(f)]));
    if (!(before < below_)) return false;
    // Candidates: the surface halfway between them (on the wedge's patch), or either point.
    std::vector<std::pair<Point3, int>> places;
    const Point3 half = (out_.points[p1] + out_.points[p2]) * 0.5;
    const Projection pr = locator_.locate(half, out_.face_patch[size_t(k)], Point3(0, 0, 0), out_.host[p1], width);
    // A junction (a point several lines run through) stays where it is: moved, it would move
    // every line through it.
    const bool fixed1 = junction(p1), fixed2 = junction(p2);
    if (pr.face >= 0 && !fixed1 && !fixed2) places.push_back({pr.point, pr.face});
    if (!fixed2) places.push_back({out_.points[p1], out_.host[p1]});
    if (!fixed1) places.push_back({out_.points[p2], out_.host[p2]});
    // The first that raises the smallest angle: halfway moves each line least.
    int chosen = -1;
    for (int n = 0; n < int(places.size()) && chosen < 0; ++n) {
      bool folds = false;
      const double after = std::min(star_min_angle(p1, dying, places[size_t(n)].first, p2, folds),
                                    star_min_angle(p2, dying, places[size_t(n)].first, p1, folds));
      if (!folds && after > before + 1e-9) chosen = n;
    }
    if (chosen < 0) return false;
    out_.points[p1] = places[size_t(chosen)].first;
    out_.host[p1] = places[size_t(chosen)].second;
    stars_.collapse(out_, p2, p1, dying);
    // Every line through p2 now runs through p1 (line b's segment to the tip is line a's).
    for (const Place& q : places_[size_t(p2)]) {
      auto& path = paths_[size_t(q.first)];
      for (int j : {q.second - 1, q.second + 1})
        if (j >= 0 && j < int(path.points.size())) {
          feature_.erase(OutputMesh::edge_key(p2, path.points[size_t(j)]));
          feature_.insert(OutputMesh::edge_key(p1, path.points[size_t(j)]));
        }
      path.points[size_t(q.second)] = p1;
      path.slidable[size_t(q.second)] = 0;
      places_[size_t(p1)].push_back(q);
    }
    for (const Place& q : places_[size_t(p1)]) paths_[size_t(q.first)].slidable[size_t(q.second)] = 0;
    if (out_.kind[size_t(p2)] == PointKind::Corner) out_.kind[size_t(p1)] = PointKind::Corner;
    places_[size_t(p2)].clear();
    merged_into_[p2] = p1;
    merged_.push_back(p1);
    return true;
  }
};

}  // namespace

std::vector<int> relax_wedge_tips(OutputMesh& out, std::vector<LinePath>& paths,
                                  std::vector<std::array<int, 2>>& feature_edges, const SurfaceLocator& locator,
                                  const SizeField& size) {
  WedgeRelaxing relaxing(out, paths, feature_edges, locator, size);
  relaxing.run();
  return relaxing.finish(feature_edges);
}

std::vector<int> close_line_gaps(OutputMesh& out, std::vector<LinePath>& paths,
                                 std::vector<std::array<int, 2>>& feature_edges, const SurfaceLocator& locator,
                                 const SizeField& size, double below_rad) {
  WedgeRelaxing relaxing(out, paths, feature_edges, locator, size);
  relaxing.close_gaps(below_rad);
  return relaxing.finish(feature_edges);
}

}  // namespace mr::remesh
