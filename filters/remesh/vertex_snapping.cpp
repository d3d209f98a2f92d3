#include "remesh/vertex_snapping.h"

#include "common/uniform_grid.h"
#include "remesh/face_rings.h"
#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mr::remesh {

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

double face_distance(const OutputMesh& out, int f, const Point3& p) {
  const auto& t = out.faces[f];
  std::array<double, 3> bary;
  return (closest_point_on_triangle(p, out.points[t[0]], out.points[t[1]], out.points[t[2]], bary) - p).Norm();
}

}  // namespace

std::vector<int> snap_to_far_vertices(OutputMesh& out, const SurfaceLocator& locator, const SizeField& size,
                         const SnapParams& params) {
  if (out.faces.empty()) return {};
  const Surface& input = locator.surface();
  const FaceRings out_rings(out.points.size(), out.faces);
  const FaceRings in_rings(input.points.size(), input.faces);
  UniformGrid grid(std::max(size.max_size(), 1e-300));
  for (size_t v = 0; v < out.points.size(); ++v)
    if (out_rings.begin[v] < out_rings.begin[v + 1]) grid.insert(int(v), out.points[v]);

  // Distance from p to the output faces around points within r of it (infinity if none). With
  // `enough`, the search stops at the first face that close: the scan over every input vertex
  // only asks whether a vertex is farther than that, and nearly all are not. Faces marked in
  // `in_star` (a candidate's star while its move is checked) are left out; `star_reached` then
  // tells whether the search met one of them, whose distances are all that the move changes.
  std::vector<char> in_star(out.faces.size(), 0);
  auto deviation = [&](const Point3& p, double r, double enough = -1.0, bool* star_reached = nullptr) {
    double best = std::numeric_limits<double>::infinity();
    grid.visit(p, r, [&](int v) {
      for (int k = out_rings.begin[v]; k < out_rings.begin[v + 1] && best > enough; ++k) {
        const int f = out_rings.item[k];
        if (!in_star[f]) best = std::min(best, face_distance(out, f, p));
        else if (star_reached) *star_reached = true;
      }
    });
    return best;
  };
  std::vector<std::pair<double, int>> far;
  for (size_t v = 0; v < input.points.size(); ++v) {
    const double h = size.at_vertex(int(v));
    const double d = deviation(input.points[v], h, params.min_deviation * h);
    if (std::isfinite(d) && d > params.min_deviation * h) far.push_back({d / h, int(v)});
  }
  std::sort(far.begin(), far.end(), std::greater<>());

  UniformGrid input_grid(std::max(size.max_size(), 1e-300));
  for (size_t v = 0; v < input.points.size(); ++v) input_grid.insert(int(v), input.points[v]);
  // Input vertices a move of point q could bring farther from the output.
  auto around = [&](int q) {
    std::vector<int> near;
    const double r = 2 * size.max_size();
    input_grid.visit(out.points[q], r, [&](int u) { if ((input.points[u] - out.points[q]).Norm() <= r) near.push_back(u); });
    return near;
  };

  // Largest distance from the input of face f's centroid and side midpoints.
  auto face_gap = [&](int f) {
    const auto& t = out.faces[f];
    const Point3 &a = out.points[t[0]], &b = out.points[t[1]], &c = out.points[t[2]];
    const Point3 normal = unit_normal(a, b, c);
    double gap = 0;
    for (const Point3& p : {(a + b + c) / 3.0, (a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5})
      gap = std::max(gap, locator.locate(p, out.face_patch[f], normal, out.host[t[0]], 2 * size.max_size()).distance);
    return gap;
  };

  std::vector<char> moved(out.points.size(), 0);
  for (const auto& [ratio, v] : far) {
    const Point3& target = input.points[v];
    const double h = size.at_vertex(v);
    const double before_deviation = deviation(target, h, params.min_deviation * h);  // earlier snaps may have fixed it
    if (!(before_deviation > params.min_deviation * h)) continue;
    // Only vertices inside one patch (and on a face: scans carry unused points): a free point
    // never goes onto a feature line.
    if (in_rings.begin[v] == in_rings.begin[v + 1]) continue;
    const int patch = input.group[in_rings.item[in_rings.begin[v]]];
    bool one_patch = true;
    for (int k = in_rings.begin[v]; k < in_rings.begin[v + 1]; ++k) one_patch = one_patch && input.group[in_rings.item[k]] == patch;
    if (!one_patch) continue;
    std::vector<std::pair<double, int>> candidates;
    grid.visit(target, params.reach * h, [&](int q) {
      if (out.kind[q] != PointKind::Free || moved[q]) return;
      const double d = (out.points[q] - target).Norm();
      if (d <= params.reach * h && out.face_patch[out_rings.item[out_rings.begin[q]]] == patch) candidates.push_back({d, q});
    });
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    for (const auto& [d, q] : candidates) {
      double old_min = 1e9;
      std::vector<Point3> old_normals;
      for (int k = out_rings.begin[q]; k < out_rings.begin[q + 1]; ++k) {
        const auto& f = out.faces[out_rings.item[k]];
        old_min = std::min(old_min, min_angle(out.points[f[0]], out.points[f[1]], out.points[f[2]]));
        old_normals.push_back(unit_normal(out.points[f[0]], out.points[f[1]], out.points[f[2]]));
      }
      // The faces around q first (cheap, and where most candidates fail), then what the move
      // does to the input vertices nearby, measured before and after it.
      const Point3 old = out.points[q];
      out.points[q] = target;
      bool ok = true;
      for (int k = out_rings.begin[q]; k < out_rings.begin[q + 1] && ok; ++k) {
        const auto& f = out.faces[out_rings.item[k]];
        const Point3 n = unit_normal(out.points[f[0]], out.points[f[1]], out.points[f[2]]);
        ok = n * old_normals[k - out_rings.begin[q]] >= 0.5 &&
             min_angle(out.points[f[0]], out.points[f[1]], out.points[f[2]]) >= std::min(old_min, params.min_angle_deg * kDeg);
      }
      if (!ok) {
        out.points[q] = old;
        continue;
      }
      // Then the faces' own distance from the input (a few lookups), before the input
      // vertices nearby (a search from each, and there may be thousands).
      std::vector<double> gaps_after;
      for (int k = out_rings.begin[q]; k < out_rings.begin[q + 1]; ++k) gaps_after.push_back(face_gap(out_rings.item[k]));
      out.points[q] = old;
      for (int k = out_rings.begin[q]; k < out_rings.begin[q + 1] && ok; ++k)
        ok = gaps_after[k - out_rings.begin[q]] <= std::max(face_gap(out_rings.item[k]), params.min_deviation * h) * (1 + 1e-9);
      if (!ok) continue;
      // Nothing nearby may end up beyond the threshold that was within it (or farther than it
      // was). The search reaches the same faces before and after the move (the grid keeps q's
      // old place meanwhile), and only the star's distances change: one search off the star per
      // input vertex, which ends at the first face within the threshold (then the vertex stays
      // within it whatever the move does; so it is for nearly all), and the star's few faces
      // before and after where it does not.
      const std::vector<int> neighbours = around(q);
      for (int k = out_rings.begin[q]; k < out_rings.begin[q + 1]; ++k) in_star[out_rings.item[k]] = 1;
      auto star_distance = [&](const Point3& p) {
        double best = std::numeric_limits<double>::infinity();
        for (int k = out_rings.begin[q]; k < out_rings.begin[q + 1]; ++k)
          best = std::min(best, face_distance(out, out_rings.item[k], p));
        return best;
      };
      for (size_t k = 0; k < neighbours.size() && ok; ++k) {
        const int u = neighbours[k];
        if (u == v) continue;
        const Point3& p = input.points[u];
        const double threshold = params.min_deviation * size.at_vertex(u);
        bool star_reached = false;
        const double off_star = deviation(p, size.at_vertex(u), threshold * (1 + 1e-9), &star_reached);
        if (off_star <= threshold * (1 + 1e-9) || !star_reached) continue;
        out.points[q] = old;
        const double before = std::max(std::min(off_star, star_distance(p)), threshold);
        out.points[q] = target;
        ok = std::min(off_star, star_distance(p)) <= before * (1 + 1e-9);
      }
      for (int k = out_rings.begin[q]; k < out_rings.begin[q + 1]; ++k) in_star[out_rings.item[k]] = 0;
      out.points[q] = target;
      if (!ok) { out.points[q] = old; continue; }
      out.host[q] = in_rings.item[in_rings.begin[v]];
      grid.insert(q, target);  // found from its new place too (the old entry only costs a visit)
      moved[q] = 1;
      break;
    }
  }
  std::vector<int> snapped;
  for (size_t q = 0; q < moved.size(); ++q)
    if (moved[q]) snapped.push_back(int(q));
  return snapped;
}

}  // namespace mr::remesh
