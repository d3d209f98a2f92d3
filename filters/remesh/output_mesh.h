// The mesh the remesher builds: flat arrays with, per vertex, its host face on the
// input surface and whether it is a corner, a point of a feature line or free.
#pragma once

#include "common/tri_mesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace mr::remesh {

enum class PointKind : char { Free = 0, Line = 1, Corner = 2 };

struct OutputMesh {
  std::vector<Point3> points;
  std::vector<int> host;         ///< host face on the input surface
  std::vector<PointKind> kind;
  std::vector<std::array<int, 3>> faces;
  std::vector<int> face_patch;   ///< input patch each face was generated in
  /// Undirected edges (min << 32 | max) of the generated faces between two line or corner
  /// points: the only points that patches share, so the front of one patch must not reuse such
  /// an edge made by another (it would get four faces). Kept up by the front only.
  std::unordered_set<std::uint64_t> shared_edges;
  /// Line segments barred to a patch meshed again (remesh.cpp): part of shared_edges while set.
  std::unordered_set<std::uint64_t> line_edges;
  /// Patches whose whole front is three sides: their triangle (sorted points) -> the patch.
  std::map<std::array<int, 3>, int> island_triangles;

  int add_point(const Point3& p, int host_face, PointKind k) {
    points.push_back(p);
    host.push_back(host_face);
    kind.push_back(k);
    return int(points.size()) - 1;
  }
  static std::uint64_t edge_key(int a, int b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
  }
  /// The edge_key of each of `edges` (feature line segments), for lookups.
  static std::unordered_set<std::uint64_t> edge_key_set(const std::vector<std::array<int, 2>>& edges) {
    std::unordered_set<std::uint64_t> keys;
    for (const auto& e : edges) keys.insert(edge_key(e[0], e[1]));
    return keys;
  }
  static std::array<int, 3> triangle_key(int a, int b, int c) {
    std::array<int, 3> t{a, b, c};
    std::sort(t.begin(), t.end());
    return t;
  }
  /// Is a->b an edge between two points that other patches may also use?
  bool is_shared(int a, int b) const { return kind[a] != PointKind::Free && kind[b] != PointKind::Free; }
  /// shared_edges again from the faces (after faces were taken out).
  void rebuild_shared_edges() {
    shared_edges = line_edges;
    for (const auto& t : faces)
      for (int z = 0; z < 3; ++z)
        if (is_shared(t[z], t[(z + 1) % 3])) shared_edges.insert(edge_key(t[z], t[(z + 1) % 3]));
  }
};

}  // namespace mr::remesh
