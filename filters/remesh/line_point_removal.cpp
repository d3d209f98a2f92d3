#include "remesh/line_point_removal.h"

#include "common/segment_geometry.h"
#include "remesh/mesh_measures.h"
#include "remesh/point_stars.h"
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

class LinePointRemoval {
public:
  LinePointRemoval(OutputMesh& out, const std::vector<std::array<int, 2>>& feature_edges, const SurfaceLocator& locator,
                   const SizeField& size)
      : out_(out), locator_(locator), size_(size), stars_(out), feature_(OutputMesh::edge_key_set(feature_edges)) {}

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
      if (stars_.of(v).empty() || before >= worse_than) { ++i; continue; }
      double best = before + 1e-9;
      int keep = -1;
      for (const size_t j : {i - 1, i + 1}) {
        const int w = path.points[j], u = path.points[j == i - 1 ? i + 1 : i - 1];
        const double after = angle_after(v, w, u, path, cumulative, i);
        if (after > best) best = after, keep = w;
      }
      if (keep < 0) { ++i; continue; }
      const int other = keep == path.points[i - 1] ? path.points[i + 1] : path.points[i - 1];
      stars_.collapse(out_, v, keep, stars_.faces_on(out_, v, keep));
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
    drop_dead_faces(out_);
    return kept_;
  }

private:
  OutputMesh& out_;
  const SurfaceLocator& locator_;
  const SizeField& size_;
  PointStars stars_;
  std::unordered_set<std::uint64_t> feature_;  // feature edges (OutputMesh::edge_key), kept up
  std::map<int, int> merged_into_;      // removed point -> the point it collapsed onto
  std::vector<int> kept_;

  double star_min_angle(int v) const {
    double worst = 1e9;
    for (int k : stars_.of(v)) worst = std::min(worst, min_angle(out_.points, out_.faces[k]));
    return worst;
  }

  double h(int v) const { return size_at_point(out_, locator_, size_, v); }

  // Smallest angle of v's faces once v (point i of the path) collapses onto its line neighbour
  // w, its other line neighbour being u; -1 when the collapse is not allowed.
  double angle_after(int v, int w, int u, const LinePath& path, const std::vector<double>& cumulative,
                     size_t i) const {
    const std::vector<int> dying = stars_.faces_on(out_, v, w);
    if (dying.empty() || dying.size() > 2 || !stars_.link_condition(out_, v, w, dying)) return -1;
    // (w and u already joined by a feature edge: the face between the two lines would go and
    // the edge would be listed twice.)
    if (feature_.count(OutputMesh::edge_key(w, u))) return -1;
    double after = 1e9;
    for (int k : stars_.of(v)) {
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
    if (point_segment_distance(out_.points[v], a, b) > bound) return -1;
    const double lo = std::min(path.arc[i - 1], path.arc[i + 1]), hi = std::max(path.arc[i - 1], path.arc[i + 1]);
    for (size_t j = 0; j < path.polyline.size(); ++j)
      if (cumulative[j] > lo && cumulative[j] < hi && point_segment_distance(path.polyline[j], a, b) > bound) return -1;
    // No new edge much longer than the size.
    const std::vector<int> nw = stars_.neighbours(out_, w);
    for (int x : stars_.neighbours(out_, v))
      if (x != w && !std::binary_search(nw.begin(), nw.end(), x) &&
          (out_.points[w] - out_.points[x]).Norm() > kLongEdge * 0.5 * (h(w) + h(x)))
        return -1;
    return after;
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
