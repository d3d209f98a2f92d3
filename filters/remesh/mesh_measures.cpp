#include "remesh/mesh_measures.h"

#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>
#include <unordered_set>

namespace mr::remesh {

namespace {

// Closest face to p, from half a size on (the output lies mostly within a fraction of a size of
// the input; one search over `reach`, a box of hundreds of faces or a walk over every long thin
// face of a CAD export, made measuring most of the filter's time), by brute force past `reach`.
Projection project(const SurfaceLocator& locator, const Point3& p, int start, double size, double reach) {
  const Projection pr = locator.locate_growing(p, -1, start, 0.5 * size, reach);
  return pr.face >= 0 ? pr : locator.locate(p, -1, Point3(0, 0, 0), start, reach);
}

double distance_to(const SurfaceLocator& locator, const Point3& p, int start, double size, double reach) {
  return project(locator, p, start, size, reach).distance;
}

/// Some face of `locator`'s surface lies within `radius` of p (`near`: scratch).
bool some_face_within(const SurfaceLocator& locator, const Point3& p, double radius, std::vector<int>& near) {
  locator.faces_near(p, radius, near);
  const Surface& s = locator.surface();
  std::array<double, 3> bary;
  for (int f : near) {
    const auto& t = s.faces[size_t(f)];
    if ((closest_point_on_triangle(p, s.points[t[0]], s.points[t[1]], s.points[t[2]], bary) - p).Norm() <= radius)
      return true;
  }
  return false;
}

}  // namespace

double size_at_point(const OutputMesh& out, const SurfaceLocator& locator, const SizeField& size, int v) {
  const int f = out.host[v];
  if (f < 0) return size.max_size();
  const Surface& s = locator.surface();
  std::array<double, 3> bary;
  closest_point_on_triangle(out.points[v], s.points[s.faces[f][0]], s.points[s.faces[f][1]], s.points[s.faces[f][2]],
                            bary);
  return size.at(f, bary);
}

Measures measure(const OutputMesh& out, const SurfaceLocator& input_locator, const SizeField& size) {
  Measures m;
  constexpr double kRad = 180.0 / 3.14159265358979323846;
  if (out.faces.empty()) return m;
  double worst = 1e9, sum = 0;
  std::vector<std::pair<int, int>> edges;  // each once, sorted (a tree's node per edge cost more)
  edges.reserve(3 * out.faces.size());
  for (const auto& f : out.faces) {
    const double a = min_angle(out.points[f[0]], out.points[f[1]], out.points[f[2]]);
    worst = std::min(worst, a);
    sum += a;
    for (int z = 0; z < 3; ++z) edges.push_back(std::minmax(f[z], f[(z + 1) % 3]));
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  m.min_angle_deg = worst * kRad;
  m.mean_min_angle_deg = sum / double(out.faces.size()) * kRad;
  const double reach = 4 * size.max_size();
  long in_range = 0;
  double haus = 0;
  for (const auto& e : edges) {
    const Point3 mid = (out.points[e.first] + out.points[e.second]) * 0.5;
    const Projection pr = project(input_locator, mid, out.host[e.first], size.max_size(), reach);
    const double h = pr.face >= 0 ? size.at(pr.face, pr.bary) : size.max_size();
    const double len = (out.points[e.first] - out.points[e.second]).Norm();
    if (len >= kShortEdge * h && len <= kLongEdge * h) in_range++;
    haus = std::max(haus, pr.distance);
  }
  m.edges_in_range = double(in_range) / double(edges.size());
  for (size_t f = 0; f < out.faces.size(); ++f) {
    const auto& t = out.faces[f];
    const Point3 c = (out.points[t[0]] + out.points[t[1]] + out.points[t[2]]) / 3.0;
    haus = std::max(haus, distance_to(input_locator, c, out.host[t[0]], size.max_size(), reach));
  }
  // Input vertices to the output surface.
  const Surface output = Surface::from_arrays(out.points, out.faces, {});
  const SurfaceLocator out_locator(output, size.max_size());
  const Surface& in = input_locator.surface();
  std::vector<int> near;
  for (const auto& p : in.points) {
    // A vertex this near some output face cannot raise `haus` (distance_to may return up to a
    // distance tie more than the nearest face's distance): one look at the few faces within it
    // settles most vertices of a fine input without the search (832k faces: a tenth of a remesh).
    const double settled = haus - 2 * (out_locator.rounding_length() + 1e-12 * haus);
    if (settled > 0 && some_face_within(out_locator, p, settled, near)) continue;
    haus = std::max(haus, distance_to(out_locator, p, -1, size.max_size(), reach));
  }
  m.hausdorff = haus;
  return m;
}

WedgeMeasure measure_wedges(const OutputMesh& out, const std::vector<std::array<int, 2>>& feature_edges) {
  constexpr double kDeg = 180.0 / 3.14159265358979323846;
  const std::unordered_set<std::uint64_t> feature = OutputMesh::edge_key_set(feature_edges);
  WedgeMeasure w;
  for (const auto& t : out.faces)
    for (int z = 0; z < 3; ++z) {
      const int a = t[z], b = t[(z + 1) % 3], c = t[(z + 2) % 3];
      const double radians = corner_angle(out.points[a], out.points[b], out.points[c]);
      const double angle = radians * kDeg;
      if (is_wedge_tip(radians, a, b, c, feature)) {
        ++w.wedge_tips;
        w.min_wedge_angle_deg = std::min(w.min_wedge_angle_deg, angle);
      } else {
        w.min_angle_off_wedges_deg = std::min(w.min_angle_off_wedges_deg, angle);
      }
    }
  return w;
}

int count_missing_edges(const OutputMesh& out, const std::vector<std::array<int, 2>>& edges) {
  std::unordered_set<std::uint64_t> present;
  for (const auto& t : out.faces)
    for (int z = 0; z < 3; ++z) present.insert(OutputMesh::edge_key(t[z], t[(z + 1) % 3]));
  int missing = 0;
  for (const auto& e : edges) missing += present.count(OutputMesh::edge_key(e[0], e[1])) == 0;
  return missing;
}

int count_pinched_points(const OutputMesh& out) {
  // Per point, the sides opposite it in its faces (CSR); one fan links them into one chain.
  const size_t n = out.points.size();
  std::vector<int> begin(n + 1, 0);
  for (const auto& t : out.faces)
    for (int v : t) ++begin[size_t(v) + 1];
  for (size_t v = 0; v < n; ++v) begin[v + 1] += begin[v];
  std::vector<std::array<int, 2>> sides(static_cast<size_t>(begin[n]));
  std::vector<int> fill(begin.begin(), begin.end() - 1);
  for (const auto& t : out.faces)
    for (int z = 0; z < 3; ++z) sides[size_t(fill[size_t(t[z])]++)] = {t[(z + 1) % 3], t[(z + 2) % 3]};
  int pinched = 0;
  std::vector<int> ids, parent;
  for (size_t v = 0; v < n; ++v) {
    ids.clear();
    for (int k = begin[v]; k < begin[v + 1]; ++k) ids.insert(ids.end(), sides[size_t(k)].begin(), sides[size_t(k)].end());
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    parent.resize(ids.size());
    for (size_t i = 0; i < ids.size(); ++i) parent[i] = int(i);
    auto find = [&](int x) {
      while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
      return x;
    };
    auto at = [&](int id) { return int(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin()); };
    int roots = int(ids.size());
    for (int k = begin[v]; k < begin[v + 1]; ++k) {
      const int a = find(at(sides[size_t(k)][0])), b = find(at(sides[size_t(k)][1]));
      if (a != b) { parent[size_t(a)] = b; --roots; }
    }
    if (roots > 1) ++pinched;
  }
  return pinched;
}

}  // namespace mr::remesh
