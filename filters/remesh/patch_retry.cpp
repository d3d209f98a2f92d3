#include "remesh/patch_retry.h"

#include <algorithm>
#include <map>
#include <set>
#include <unordered_map>

namespace mr::remesh {

std::vector<int> pinched_points(const OutputMesh& out, int patch) {
  // Per point, the sides opposite it in the patch's faces: one fan links them into one chain.
  std::unordered_map<int, std::vector<std::array<int, 2>>> link;
  for (size_t f = 0; f < out.faces.size(); ++f) {
    if (out.face_patch[f] != patch) continue;
    const auto& t = out.faces[f];
    for (int z = 0; z < 3; ++z) link[t[z]].push_back({t[(z + 1) % 3], t[(z + 2) % 3]});
  }
  std::vector<int> pinched;
  for (const auto& [v, sides] : link) {
    // Components of the link graph by union-find over its points.
    std::unordered_map<int, int> parent, degree;
    auto find = [&](int x) {
      if (!parent.count(x)) parent[x] = x;
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (const auto& s : sides) {
      parent[find(s[0])] = find(s[1]);
      ++degree[s[0]];
      ++degree[s[1]];
    }
    int roots = 0;
    for (const auto& [x, p] : parent) roots += find(x) == x ? 1 : 0;
    if (roots < 2) continue;
    // A free point lies inside the patch: its faces make one fan. A line or corner point may
    // border the patch more than once (a patch around a dangling line, or wrapping round), but
    // no fan may close round it then: a closed fan leaves no room at the point for other faces.
    // (seed 40 of fuzz_union --models: a patch's front closed a fan round a corner it also
    // bordered elsewhere; checking free points only, no repair saw it.)
    bool pinch = out.kind[v] == PointKind::Free;
    if (!pinch) {
      std::unordered_map<int, bool> open;  // fan (component root) -> has a link end
      for (const auto& [x, d] : degree) open[find(x)] = open[find(x)] || d != 2;
      for (const auto& [root, is_open] : open) pinch = pinch || !is_open;
    }
    if (pinch) pinched.push_back(v);
  }
  std::sort(pinched.begin(), pinched.end());  // link is a hash map: fix the order
  return pinched;
}

std::vector<int> patches_on_taken_lines(const OutputMesh& out, const std::vector<std::array<int, 2>>& feature_edges) {
  std::unordered_map<std::uint64_t, std::vector<int>> faces_of;  // line segment -> its faces
  for (const auto& e : feature_edges) faces_of.emplace(OutputMesh::edge_key(e[0], e[1]), std::vector<int>());
  for (size_t f = 0; f < out.faces.size(); ++f)
    for (int z = 0; z < 3; ++z) {
      const auto it = faces_of.find(OutputMesh::edge_key(out.faces[f][z], out.faces[f][(z + 1) % 3]));
      if (it != faces_of.end()) it->second.push_back(int(f));
    }
  std::set<int> patches;
  for (const auto& [key, faces] : faces_of) {
    if (faces.size() <= 2) continue;
    std::map<int, int> per_patch;
    for (int f : faces) per_patch[out.face_patch[size_t(f)]]++;
    for (const auto& [patch, count] : per_patch)
      if (count >= 2) patches.insert(patch);
  }
  return std::vector<int>(patches.begin(), patches.end());
}

void remove_patch_faces(OutputMesh& out, int patch) {
  std::vector<std::array<int, 3>> faces;
  std::vector<int> face_patch;
  for (size_t f = 0; f < out.faces.size(); ++f)
    if (out.face_patch[f] != patch) { faces.push_back(out.faces[f]); face_patch.push_back(out.face_patch[f]); }
  out.faces = std::move(faces);
  out.face_patch = std::move(face_patch);
  out.rebuild_shared_edges();
}

}  // namespace mr::remesh
