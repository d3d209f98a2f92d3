#include "remesh/size_field.h"

#include "common/uniform_grid.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>

namespace mr::remesh {

SizeField::SizeField(const Surface& surface, const SizeParams& params)
    : surface_(surface), vertex_size_(surface.points.size(), params.target_length) {
  const Surface& s = surface;
  if (params.max_surface_error > 0) {
    // Curvature across each interior edge of a group: dihedral angle over the distance of the
    // face centroids (the radius of the circle through both faces is about distance/angle).
    for (size_t f = 0; f < s.faces.size(); ++f)
      for (int z = 0; z < 3; ++z) {
        const int g = s.neighbour[f][z];
        if (g < int(f) || s.group[g] != s.group[f]) continue;
        const double c = std::clamp(s.face_normal[f] * s.face_normal[g], -1.0, 1.0);
        const double angle = std::acos(c);
        if (angle <= 1e-9) continue;
        Point3 cf(0, 0, 0), cg(0, 0, 0);
        for (int k = 0; k < 3; ++k) { cf += s.points[s.faces[f][k]] / 3.0; cg += s.points[s.faces[g][k]] / 3.0; }
        const double radius = (cf - cg).Norm() / angle;
        const double h = std::sqrt(8.0 * params.max_surface_error * radius);
        const int a = s.faces[f][z], b = s.faces[f][(z + 1) % 3];
        // Never below a twentieth of the target: very sharp but unmarked bends stay affordable.
        const double hh = std::max(h, params.target_length / 20.0);
        vertex_size_[a] = std::min(vertex_size_[a], hh);
        vertex_size_[b] = std::min(vertex_size_[b], hh);
      }
  }
  // Sources: h <= size at the source + slope x distance. Sizes start at or below the target,
  // so a source reaches no farther than (target - its size) / slope; a grid of the vertices
  // limits each source to those (a lines layer as source has thousands of segments).
  const double slope = std::max(params.gradation - 1.0, 0.0);
  const double target = params.target_length;
  auto reach_of = [&](double h) { return slope > 0 ? std::max(target - h, 0.0) / slope : -1.0; };
  double widest = 0;
  for (double h : params.source_sizes) widest = std::max(widest, reach_of(h));
  UniformGrid vertices(std::max(target, widest / 4));
  for (size_t v = 0; v < s.points.size(); ++v) vertices.insert(int(v), s.points[v]);
  // Calls f(v) for the vertices within `reach` of the box centred at c with half-size `half`
  // (every vertex when slope is 0: then a source lowers the size everywhere).
  auto visit_within = [&](const Point3& c, double half, double reach, auto&& f) {
    if (reach < 0) {
      for (size_t v = 0; v < s.points.size(); ++v) f(int(v));
    } else {
      vertices.visit(c, half + reach, f);
    }
  };
  for (size_t i = 0; i < params.source_points.size() && i < params.source_sizes.size(); ++i) {
    const Point3& at = params.source_points[i];
    const double hs = params.source_sizes[i];
    visit_within(at, 0.0, reach_of(hs), [&](int v) {
      const double h = hs + slope * (s.points[v] - at).Norm();
      if (h > 0) vertex_size_[v] = std::min(vertex_size_[v], h);
    });
  }
  for (const auto& seg : params.source_segments) {
    const Point3 &a = params.source_points[seg[0]], &b = params.source_points[seg[1]];
    const double ha = params.source_sizes[seg[0]], hb = params.source_sizes[seg[1]];
    const Point3 d = b - a;
    const double len2 = d.SquaredNorm();
    const Point3 mid = (a + b) * 0.5;
    const double half = std::max({std::abs(d[0]), std::abs(d[1]), std::abs(d[2])}) * 0.5;
    visit_within(mid, half, reach_of(std::min(ha, hb)), [&](int v) {
      // Closest point of the segment; its size interpolated between the ends, then graded.
      const double t = len2 > 0 ? std::clamp(((s.points[v] - a) * d) / len2, 0.0, 1.0) : 0.0;
      const double h = (1 - t) * ha + t * hb + slope * (s.points[v] - (a + d * t)).Norm();
      if (h > 0) vertex_size_[v] = std::min(vertex_size_[v], h);
    });
  }
  if (params.cap_gradation <= params.gradation) {
    for (size_t v = 0; v < params.vertex_cap.size() && v < vertex_size_.size(); ++v)
      if (params.vertex_cap[v] > 0) vertex_size_[v] = std::min(vertex_size_[v], params.vertex_cap[v]);
    limit_gradation(params.gradation);
  } else {
    // The caps grade on their own, faster, and the field is the smaller of the two.
    limit_gradation(params.gradation);
    std::vector<double> capped(vertex_size_.size(), std::numeric_limits<double>::max());
    for (size_t v = 0; v < params.vertex_cap.size() && v < vertex_size_.size(); ++v)
      if (params.vertex_cap[v] > 0) capped[v] = params.vertex_cap[v];
    std::swap(capped, vertex_size_);
    limit_gradation(params.cap_gradation);
    for (size_t v = 0; v < vertex_size_.size(); ++v) vertex_size_[v] = std::min(vertex_size_[v], capped[v]);
  }
  update_range();
}

SizeField::SizeField(const Surface& surface, std::vector<double> vertex_size)
    : surface_(surface), vertex_size_(std::move(vertex_size)) {
  update_range();
}

// Dijkstra-like sweep from the smallest sizes: h(v) <= h(u) + (g-1)|uv| along input edges.
void SizeField::limit_gradation(double gradation) {
  const double slope = std::max(gradation - 1.0, 0.0);
  const Surface& s = surface_;
  std::vector<std::vector<int>> adj(s.points.size());
  for (const auto& f : s.faces)
    for (int z = 0; z < 3; ++z) adj[f[z]].push_back(f[(z + 1) % 3]), adj[f[(z + 1) % 3]].push_back(f[z]);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (size_t v = 0; v < vertex_size_.size(); ++v) queue.push({vertex_size_[v], int(v)});
  while (!queue.empty()) {
    auto [h, u] = queue.top();
    queue.pop();
    if (h > vertex_size_[u]) continue;
    for (int v : adj[u]) {
      const double limit = h + slope * (s.points[u] - s.points[v]).Norm();
      if (limit < vertex_size_[v]) { vertex_size_[v] = limit; queue.push({limit, v}); }
    }
  }
}

SizeField SizeField::scaled(double factor) const {
  std::vector<double> sizes(vertex_size_);
  for (double& h : sizes) h *= factor;
  return SizeField(surface_, std::move(sizes));
}

void SizeField::update_range() {
  if (vertex_size_.empty()) return;
  min_ = *std::min_element(vertex_size_.begin(), vertex_size_.end());
  max_ = *std::max_element(vertex_size_.begin(), vertex_size_.end());
}

double SizeField::at(int face, const std::array<double, 3>& bary) const {
  if (face < 0) return max_;
  const auto& f = surface_.faces[face];
  return bary[0] * vertex_size_[f[0]] + bary[1] * vertex_size_[f[1]] + bary[2] * vertex_size_[f[2]];
}

}  // namespace mr::remesh
