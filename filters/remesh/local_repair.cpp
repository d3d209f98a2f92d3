#include "remesh/local_repair.h"

#include "common/flat_index_map.h"
#include "common/uniform_grid.h"
#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <cstdint>

namespace mr::remesh {

namespace {

std::uint64_t directed(int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); }

}  // namespace

std::vector<FrontSide> open_hole_around(OutputMesh& out, int patch, const std::vector<FrontSide>& initial_front,
                                        const std::vector<FrontSide>& open_sides, const std::vector<int>& spot_points,
                                        double radius) {
  std::vector<int> spots(spot_points);
  for (const auto& s : open_sides) spots.insert(spots.end(), {s[0], s[1]});
  if (spots.empty()) return {};
  UniformGrid grid(radius);
  for (int v : spots) grid.insert(v, out.points[v]);
  auto near_spot = [&](int v) {
    bool near = false;
    grid.visit(out.points[v], radius, [&](int w) { near = near || (out.points[v] - out.points[w]).Norm() <= radius; });
    return near;
  };

  std::vector<std::array<int, 3>> kept, removed;
  std::vector<int> kept_patch;
  for (size_t f = 0; f < out.faces.size(); ++f) {
    const auto& t = out.faces[f];
    if (out.face_patch[f] == patch && (near_spot(t[0]) || near_spot(t[1]) || near_spot(t[2]))) {
      removed.push_back(t);
    } else {
      kept.push_back(t);
      kept_patch.push_back(out.face_patch[f]);
    }
  }
  // (Flat tables: a repair round scans the whole output, and node-based sets made these and
  // bad_edges' count a fifth of box.STL's regrid.)
  FlatIndexMap<std::uint64_t> kept_sides, initial;
  kept_sides.reserve(3 * kept.size());
  for (const auto& t : kept)
    for (int z = 0; z < 3; ++z) kept_sides.emplace(directed(t[z], t[(z + 1) % 3]), 0);
  for (const auto& s : initial_front) initial.emplace(directed(s[0], s[1]), 0);
  // The unmeshed part lies left of a side: a removed face's side a->b now borders the hole, and
  // is a front side where something stays on its right (a kept face, or the patch's border).
  std::vector<FrontSide> front;
  auto borders = [&](int a, int b) { return kept_sides.find(directed(b, a)) || initial.find(directed(a, b)); };
  for (const auto& t : removed)
    for (int z = 0; z < 3; ++z)
      if (borders(t[z], t[(z + 1) % 3])) front.push_back({t[z], t[(z + 1) % 3]});
  for (const auto& s : open_sides)
    if (borders(s[0], s[1])) front.push_back(s);
  std::sort(front.begin(), front.end());
  front.erase(std::unique(front.begin(), front.end()), front.end());

  out.faces = std::move(kept);
  out.face_patch = std::move(kept_patch);
  out.rebuild_shared_edges();
  return front;
}

std::vector<int> oversized_face_points(const OutputMesh& out, int patch, double max_length, double needle_length,
                                       double needle_angle) {
  std::vector<int> points;
  for (size_t f = 0; f < out.faces.size(); ++f) {
    if (out.face_patch[f] != patch) continue;
    const auto& t = out.faces[f];
    const Point3 &a = out.points[t[0]], &b = out.points[t[1]], &c = out.points[t[2]];
    const double longest = std::max({(b - a).Norm(), (c - b).Norm(), (a - c).Norm()});
    if (longest > max_length || (longest > needle_length && min_angle(a, b, c) < needle_angle))
      points.insert(points.end(), t.begin(), t.end());
  }
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

std::vector<int> stray_face_points(const OutputMesh& out, int patch, const SurfaceLocator& locator, double max_distance) {
  std::vector<int> points;
  for (size_t f = 0; f < out.faces.size(); ++f) {
    if (out.face_patch[f] != patch) continue;
    const auto& t = out.faces[f];
    const Point3 centroid = (out.points[t[0]] + out.points[t[1]] + out.points[t[2]]) / 3.0;
    if (locator.locate_growing(centroid, patch, out.host[t[0]], 0.25 * max_distance, max_distance).face < 0)
      points.insert(points.end(), t.begin(), t.end());
  }
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

std::vector<int> faces_around(const OutputMesh& out, int patch, const std::vector<FrontSide>& front) {
  std::vector<char> on_front(out.points.size(), 0);
  for (const auto& s : front) on_front[size_t(s[0])] = on_front[size_t(s[1])] = 1;
  std::vector<int> faces;
  for (size_t f = 0; f < out.faces.size(); ++f) {
    const auto& t = out.faces[f];
    if (out.face_patch[f] == patch && (on_front[size_t(t[0])] || on_front[size_t(t[1])] || on_front[size_t(t[2])]))
      faces.push_back(int(f));
  }
  return faces;
}

int bad_edges(const OutputMesh& out) {
  FlatIndexMap<std::uint64_t> count;  // directed side -> faces
  count.reserve(out.faces.size() * 3);
  int bad = 0;  // sides held by more than one face, each once (when its second face comes)
  for (const auto& t : out.faces)
    for (int z = 0; z < 3; ++z) {
      const std::uint64_t side = directed(t[z], t[(z + 1) % 3]);
      const auto [n, added] = count.emplace(side, 1);
      if (added) continue;
      if (n == 1) ++bad;
      count.assign(side, n + 1);
    }
  return bad;
}

}  // namespace mr::remesh
