#include "remesh/corner_merging.h"

#include "common/union_find.h"
#include "remesh/feature_front.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>

namespace mr::remesh {

namespace {

// The last face (in face order) whose ridge side runs a -> b, or -1.
int ridge_face(const features::Result& fr, const Surface& s, const FaceRings& rings, int a, int b) {
  int found = -1;
  for (int k = rings.begin[a]; k < rings.begin[a + 1]; ++k) {
    const int f = rings.item[k];
    for (int z = 0; z < 3; ++z)
      if (fr.ridge[f][z] && s.faces[f][z] == a && s.faces[f][(z + 1) % 3] == b) found = f;
  }
  return found;
}

// A step: lines i and j lie within kSliverGap x the smallest size on them of each other, and
// the surface beyond them goes on the same way (the faces across each line's first edge from
// the patch they share within kStepTurnDeg of each other). Around a thin plate's rim the surfaces
// beyond face apart: merged there, its top and bottom would meet in a knife edge.
constexpr double kStepTurnDeg = 30.0;
bool step_twins(const features::Result& fr, const Surface& s, const FaceRings& rings, const SizeField& size, size_t i,
                size_t j) {
  if (!within_sliver_gap(s, size, fr.lines[i].vertices, fr.lines[j].vertices)) return false;
  auto sides = [&](size_t line) {
    const auto& v = fr.lines[line].vertices;
    return std::array<int, 2>{ridge_face(fr, s, rings, v[0], v[1]), ridge_face(fr, s, rings, v[1], v[0])};
  };
  const auto si = sides(i), sj = sides(j);
  if (std::min({si[0], si[1], sj[0], sj[1]}) < 0) return false;
  for (int p : si)
    for (int q : sj)
      if (s.group[p] == s.group[q]) {  // the strip between them; beyond it, the other faces
        const int beyond_i = si[0] == p ? si[1] : si[0], beyond_j = sj[0] == q ? sj[1] : sj[0];
        return s.face_normal[beyond_i] * s.face_normal[beyond_j] >= std::cos(kStepTurnDeg * 3.14159265358979323846 / 180.0);
      }
  return false;
}

double polyline_length(const Surface& s, const std::vector<int>& chain) {
  double length = 0;
  for (size_t k = 0; k + 1 < chain.size(); ++k) length += (s.points[chain[k + 1]] - s.points[chain[k]]).Norm();
  return length;
}

}  // namespace

CornerMerging CornerMerging::none(const features::Result& fr, const Surface& s) {
  CornerMerging cm;
  cm.representative.resize(s.points.size());
  std::iota(cm.representative.begin(), cm.representative.end(), 0);
  cm.dropped_line.assign(fr.lines.size(), 0);
  cm.dropped_patch.assign(fr.patch_count, 0);
  return cm;
}

CornerMerging merge_close_corners(const features::Result& fr, const Surface& s, const FaceRings& rings,
                                  const SizeField& size) {
  const int n = int(s.points.size());
  CornerMerging cm = CornerMerging::none(fr, s);
  std::vector<char> corner(n, 0);
  for (int c : fr.corners) corner[c] = 1;
  std::vector<int> degree(n, 0);
  for (const auto& line : fr.lines)
    if (!line.closed && line.vertices.size() >= 2) { ++degree[line.vertices.front()]; ++degree[line.vertices.back()]; }

  // Tiny lines join their end corners into groups.
  UnionFind joined(n);
  std::vector<char> tiny(fr.lines.size(), 0);
  for (size_t i = 0; i < fr.lines.size(); ++i) {
    const auto& v = fr.lines[i].vertices;
    if (fr.lines[i].closed || v.size() < 2 || v.front() == v.back() || !corner[v.front()] || !corner[v.back()]) continue;
    const double h = std::min(size.at_vertex(v.front()), size.at_vertex(v.back()));
    if (polyline_length(s, v) >= kTinyLine * h) continue;
    tiny[i] = 1;
    joined.unite(v.front(), v.back());
  }
  std::map<int, std::vector<int>> members;  // root -> corners, increasing
  for (int c : fr.corners) members[joined.find(c)].push_back(c);
  std::vector<int> group_of(n, -1);  // per vertex: the group it lies in (corners and tiny lines' vertices)
  std::vector<std::vector<int>> groups;
  std::vector<int> rep;
  for (auto& [root, corners] : members) {
    if (corners.size() < 2) continue;
    const int g = int(groups.size());
    int best = corners[0];
    for (int c : corners)
      if (degree[c] > degree[best]) best = c;
    for (int c : corners) group_of[c] = g;
    groups.push_back(corners);
    rep.push_back(best);
  }
  if (groups.empty()) return cm;
  std::vector<char> refused(groups.size(), 0);
  for (size_t g = 0; g < groups.size(); ++g)
    for (int c : groups[g])
      if ((s.points[c] - s.points[rep[g]]).Norm() > kTinyLine * size.at_vertex(rep[g])) refused[g] = 1;
  for (size_t i = 0; i < fr.lines.size(); ++i) {
    const auto& v = fr.lines[i].vertices;
    if (fr.lines[i].closed || v.size() < 2) continue;
    const int g = group_of[v.front()];
    if (g < 0 || g != group_of[v.back()]) continue;
    if (!tiny[i] && v.front() != v.back()) refused[g] = 1;  // it would become a loop at the point
    if (tiny[i])
      for (int x : v) group_of[x] = g;
  }
  // Each patch may meet a group along one run of its border only: count the border sides
  // entering the group, per group and patch; a patch bordered by the group alone vanishes.
  std::map<std::pair<int, int>, int> entries;
  std::vector<int> border_sides(fr.patch_count, 0), inside_sides(fr.patch_count, 0);
  std::vector<int> inside_group(fr.patch_count, -1), other_group(fr.patch_count, -1);
  std::vector<double> patch_area(fr.patch_count, 0.0);
  for (size_t f = 0; f < s.faces.size(); ++f) {
    const auto& t = s.faces[f];
    const int p = s.group[f];
    patch_area[p] += 0.5 * ((s.points[t[1]] - s.points[t[0]]) ^ (s.points[t[2]] - s.points[t[0]])).Norm();
    for (int z = 0; z < 3; ++z) {
      if (!fr.ridge[f][z]) continue;
      const int gx = group_of[t[z]], gy = group_of[t[(z + 1) % 3]];
      ++border_sides[p];
      // A dangling line, the patch on both sides, leaves the group and comes back without a pinch.
      const int across = s.neighbour[f][z];
      const bool dangling = across >= 0 && s.group[across] == p;
      if (gy >= 0 && gx != gy && !dangling) ++entries[{gy, p}];
      if (gx >= 0 && gx == gy) {
        ++inside_sides[p];
        if (inside_group[p] >= 0 && inside_group[p] != gx) other_group[p] = inside_group[p];
        inside_group[p] = gx;
      }
    }
  }
  for (const auto& [key, count] : entries)
    if (count > 1) refused[key.first] = 1;
  std::vector<int> vanishing;
  for (int p = 0; p < fr.patch_count; ++p) {
    if (border_sides[p] == 0 || inside_sides[p] != border_sides[p]) continue;
    const int g = inside_group[p];
    if (other_group[p] >= 0) {  // bordered by two groups' tiny lines only: it would shrink to two points
      refused[g] = refused[other_group[p]] = 1;
      continue;
    }
    const double h = kTinyLine * size.at_vertex(rep[g]);
    if (patch_area[p] > h * h) refused[g] = 1;  // the rest of a closed body around a tiny patch
    else vanishing.push_back(p);
  }
  // Two lines that would join the same two points, where they did not before, close a lens
  // between them (a triangle of corners loses a side): no better than the tiny line, unless
  // they are twins along a step (a ledge 0.002 high between plates, box.STL united), which then
  // share their points (feature_front.cpp).
  auto mapped = [&](int v) {
    const int g = group_of[v];
    return g >= 0 && !refused[g] && corner[v] ? rep[g] : v;
  };
  auto ends_of = [&](size_t i) -> std::pair<int, int> { return std::minmax(fr.lines[i].vertices.front(), fr.lines[i].vertices.back()); };
  auto key_of = [&](size_t i) -> std::pair<int, int> { return std::minmax(mapped(fr.lines[i].vertices.front()), mapped(fr.lines[i].vertices.back())); };
  auto refuse_lens = [&](size_t i, size_t j) {
    if (step_twins(fr, s, rings, size, i, j)) return;
    for (int x : {fr.lines[i].vertices.front(), fr.lines[i].vertices.back(), fr.lines[j].vertices.front(), fr.lines[j].vertices.back()})
      if (group_of[x] >= 0 && corner[x]) refused[group_of[x]] = 1;
  };
  std::map<std::pair<int, int>, size_t> first_moved;  // mapped ends -> the first line the merge moves there
  std::vector<char> open_line(fr.lines.size(), 0);
  for (size_t i = 0; i < fr.lines.size(); ++i)
    open_line[i] = !fr.lines[i].closed && fr.lines[i].vertices.size() >= 2 && !tiny[i];
  for (size_t i = 0; i < fr.lines.size(); ++i) {
    if (!open_line[i] || key_of(i) == ends_of(i)) continue;
    const auto [it, fresh] = first_moved.insert({key_of(i), i});
    if (!fresh && ends_of(it->second) != ends_of(i)) refuse_lens(i, it->second);
  }
  for (size_t i = 0; i < fr.lines.size(); ++i) {
    if (!open_line[i] || key_of(i) != ends_of(i)) continue;
    auto it = first_moved.find(key_of(i));  // an unmoved line the merge gives a new twin
    if (it != first_moved.end() && ends_of(it->second) != ends_of(i)) refuse_lens(i, it->second);
  }
  for (size_t g = 0; g < groups.size(); ++g) {
    if (refused[g]) continue;
    for (int c : groups[g])
      if (c != rep[g]) { cm.representative[c] = rep[g]; ++cm.merged_corners; }
  }
  for (size_t i = 0; i < fr.lines.size(); ++i)
    if (tiny[i] && !refused[group_of[fr.lines[i].vertices.front()]]) cm.dropped_line[i] = 1;
  for (int p : vanishing)
    if (!refused[inside_group[p]]) cm.dropped_patch[p] = 1;
  return cm;
}

}  // namespace mr::remesh
