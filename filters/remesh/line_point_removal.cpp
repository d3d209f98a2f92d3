#include "remesh/line_point_removal.h"

#include "remesh/mesh_measures.h"
#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <unordered_set>

namespace mr::remesh {

namespace {

// The merged segment may leave the input polyline (and the removed point) this far, x the size
// at the removed point: the bound of a free point's collapse (length_equalisation.cpp).
constexpr double kDeviation = 0.05;
// New faces may not turn by more than acos(0.7) from the faces they replace.
constexpr double kFoldCos = 0.7;

double distance_to_segment(const Point3& p, const Point3& a, const Point3& b) {
  const Point3 ab = b - a;
  const double len2 = ab.SquaredNorm();
  const double t = len2 > 0 ? std::clamp(((p - a) * ab) / len2, 0.0, 1.0) : 0.0;
  return (a + ab * t - p).Norm();
}

class LinePointRemoval {
public:
  LinePointRemoval(OutputMesh& out, const std::vector<std::array<int, 2>>& feature_edges, const SurfaceLocator& locator,
                   const SizeField& size)
      : out_(out), locator_(locator), size_(size), star_(out.points.size()) {
    for (size_t f = 0; f < out.faces.size(); ++f)
      for (int v : out.faces[f]) star_[v].push_back(int(f));
    for (const auto& e : feature_edges) feature_.insert(OutputMesh::edge_key(e[0], e[1]));
  }

  /// Removes the path's points that qualify, in order along it.
  void run(LinePath& path, double worse_than) {
    if (path.polyline.size() < 2) return;
    std::vector<double> cumulative(path.polyline.size(), 0.0);
    for (size_t j = 1; j < path.polyline.size(); ++j)
      cumulative[j] = cumulative[j - 1] + (path.polyline[j] - path.polyline[j - 1]).Norm();
    const bool closed = path.points.front() == path.points.back();
    for (size_t i = 1; i + 1 < path.points.size();) {
      // A closed line keeps three segments (two would run there and back).
      if (closed && path.points.size() <= 4) return;
      const int v = path.points[i];
      const double before = path.slidable[i] ? star_min_angle(v) : 1e9;
      if (star_[v].empty() || before >= worse_than) { ++i; continue; }
      double best = before + 1e-9;
      int keep = -1;
      for (const size_t j : {i - 1, i + 1}) {
        const int w = path.points[j], u = path.points[j == i - 1 ? i + 1 : i - 1];
        const double after = angle_after(v, w, u, path, cumulative, i);
        if (after > best) best = after, keep = w;
      }
      if (keep < 0) { ++i; continue; }
      const int other = keep == path.points[i - 1] ? path.points[i + 1] : path.points[i - 1];
      collapse(v, keep);
      feature_.erase(OutputMesh::edge_key(v, keep));
      feature_.erase(OutputMesh::edge_key(v, other));
      feature_.insert(OutputMesh::edge_key(keep, other));
      merged_into_[v] = keep;
      kept_.push_back(keep);
      path.points.erase(path.points.begin() + std::ptrdiff_t(i));
      path.arc.erase(path.arc.begin() + std::ptrdiff_t(i));
      path.slidable.erase(path.slidable.begin() + std::ptrdiff_t(i));
    }
  }

  /// The feature edges with the removed points' segments merged; dead faces dropped.
  std::vector<int> finish(std::vector<std::array<int, 2>>& feature_edges) {
    auto final_point = [&](int x) {
      for (auto it = merged_into_.find(x); it != merged_into_.end(); it = merged_into_.find(x)) x = it->second;
      return x;
    };
    std::vector<std::array<int, 2>> edges;
    for (const auto& e : feature_edges) {
      const int a = final_point(e[0]), b = final_point(e[1]);
      if (a != b) edges.push_back({a, b});
    }
    // A removed point's two segments become one: (v,w) goes, (v,u) becomes (w,u).
    std::vector<std::array<int, 2>> unique;
    std::unordered_set<std::uint64_t> seen;
    for (const auto& e : edges)
      if (seen.insert(OutputMesh::edge_key(e[0], e[1])).second) unique.push_back(e);
    if (!merged_into_.empty()) feature_edges = std::move(unique);
    size_t n = 0;
    for (size_t f = 0; f < out_.faces.size(); ++f) {
      if (out_.faces[f][0] < 0) continue;
      out_.faces[n] = out_.faces[f];
      out_.face_patch[n++] = out_.face_patch[f];
    }
    out_.faces.resize(n);
    out_.face_patch.resize(n);
    return kept_;
  }

private:
  OutputMesh& out_;
  const SurfaceLocator& locator_;
  const SizeField& size_;
  std::vector<std::vector<int>> star_;  // live faces around each point
  std::unordered_set<std::uint64_t> feature_;  // feature edges (OutputMesh::edge_key), kept up
  std::map<int, int> merged_into_;      // removed point -> the point it collapsed onto
  std::vector<int> kept_;

  double star_min_angle(int v) const {
    double worst = 1e9;
    for (int k : star_[v]) worst = std::min(worst, min_angle(out_.points, out_.faces[k]));
    return worst;
  }

  std::vector<int> neighbours(int v) const {
    std::vector<int> n;
    for (int k : star_[v])
      for (int x : out_.faces[k])
        if (x != v) n.push_back(x);
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
    return n;
  }

  std::vector<int> faces_on(int v, int w) const {
    std::vector<int> on;
    for (int k : star_[v]) {
      const auto& t = out_.faces[k];
      if (t[0] == w || t[1] == w || t[2] == w) on.push_back(k);
    }
    return on;
  }

  double h(int v) const { return size_at_point(out_, locator_, size_, v); }

  // Smallest angle of v's faces once v (point i of the path) collapses onto its line neighbour
  // w, its other line neighbour being u; -1 when the collapse is not allowed.
  double angle_after(int v, int w, int u, const LinePath& path, const std::vector<double>& cumulative,
                     size_t i) const {
    const std::vector<int> dying = faces_on(v, w);
    if (dying.empty() || dying.size() > 2) return -1;
    // Link condition: v and w share no neighbour but the third points of the dying faces.
    std::vector<int> opposite;
    for (int k : dying)
      for (int x : out_.faces[k])
        if (x != v && x != w) opposite.push_back(x);
    std::sort(opposite.begin(), opposite.end());
    const std::vector<int> nv = neighbours(v), nw = neighbours(w);
    std::vector<int> common;
    std::set_intersection(nv.begin(), nv.end(), nw.begin(), nw.end(), std::back_inserter(common));
    if (common != opposite) return -1;
    // (w and u already joined by a feature edge: the face between the two lines would go and
    // the edge would be listed twice.)
    if (feature_.count(OutputMesh::edge_key(w, u))) return -1;
    double after = 1e9;
    for (int k : star_[v]) {
      if (std::find(dying.begin(), dying.end(), k) != dying.end()) continue;
      const auto& t = out_.faces[k];
      std::array<Point3, 3> q;
      for (int z = 0; z < 3; ++z) q[z] = out_.points[t[z] == v ? w : t[z]];
      const Point3 n_old = unit_normal(out_.points[t[0]], out_.points[t[1]], out_.points[t[2]]);
      if (unit_normal(q[0], q[1], q[2]) * n_old < kFoldCos) return -1;
      after = std::min(after, min_angle(q[0], q[1], q[2]));
    }
    // The merged segment follows the input line: its polyline between w and u, and v itself.
    const double bound = kDeviation * h(v);
    const Point3 &a = out_.points[w], &b = out_.points[u];
    if (distance_to_segment(out_.points[v], a, b) > bound) return -1;
    const double lo = std::min(path.arc[i - 1], path.arc[i + 1]), hi = std::max(path.arc[i - 1], path.arc[i + 1]);
    for (size_t j = 0; j < path.polyline.size(); ++j)
      if (cumulative[j] > lo && cumulative[j] < hi && distance_to_segment(path.polyline[j], a, b) > bound) return -1;
    // No new edge much longer than the size.
    for (int x : nv)
      if (x != w && !std::binary_search(nw.begin(), nw.end(), x) &&
          (out_.points[w] - out_.points[x]).Norm() > kLongEdge * 0.5 * (h(w) + h(x)))
        return -1;
    return after;
  }

  void collapse(int v, int w) {
    for (int k : faces_on(v, w)) {
      for (int x : out_.faces[k]) {
        auto& s = star_[x];
        s.erase(std::remove(s.begin(), s.end(), k), s.end());
      }
      out_.faces[k] = {-1, -1, -1};
    }
    for (int k : star_[v]) {
      for (int& x : out_.faces[k])
        if (x == v) x = w;
      star_[w].push_back(k);
    }
    star_[v].clear();
  }
};

}  // namespace

std::vector<int> remove_line_points(OutputMesh& out, std::vector<LinePath>& paths,
                                    std::vector<std::array<int, 2>>& feature_edges, const SurfaceLocator& locator,
                                    const SizeField& size, double worse_than_rad) {
  LinePointRemoval removal(out, feature_edges, locator, size);
  for (LinePath& path : paths) removal.run(path, worse_than_rad);
  return removal.finish(feature_edges);
}

}  // namespace mr::remesh
