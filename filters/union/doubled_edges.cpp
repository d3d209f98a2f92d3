#include "union/doubled_edges.h"

#include <algorithm>

namespace mr::surface_union {

namespace {

void link(std::vector<int>& partner, int a, int b) {
  partner[size_t(a)] = b;
  if (b >= 0) partner[size_t(b)] = a;
}

/// Splits the copy made of face f's side z (u -> w, third corner c) and face g's side y
/// (w -> u, third d) at the new vertex m: f keeps (u, m, c), g keeps (w, m, d), and
/// (m, w, c), (m, u, d) follow. Halves keep their side's line flag, the new inner sides
/// have none; partners follow the sides.
void split_copy(Result& r, std::vector<char>& cut, std::vector<int>& partner, int f, int z, int g, int y, int m) {
  const int nf = int(r.faces.size()), ng = nf + 1;
  partner.resize(partner.size() + 6, -1);
  for (const auto [face, side, fresh] : {std::array<int, 3>{f, z, nf}, std::array<int, 3>{g, y, ng}}) {
    const std::array<int, 3> t = r.faces[size_t(face)];
    const std::array<bool, 3> line = r.line_edge[size_t(face)];
    const int s1 = (side + 1) % 3, s2 = (side + 2) % 3;
    const int to = t[size_t(s1)], third = t[size_t(s2)];
    const int across_to_third = partner[size_t(3 * face + s1)];  // side (to -> third)
    r.faces[size_t(face)][size_t(s1)] = m;                      // (from, m, third)
    r.line_edge[size_t(face)] = {};
    r.line_edge[size_t(face)][size_t(side)] = line[size_t(side)];
    r.line_edge[size_t(face)][size_t(s2)] = line[size_t(s2)];
    r.faces.push_back({m, to, third});
    if (!r.face_source.empty()) r.face_source.push_back(r.face_source[size_t(face)]);
    r.line_edge.push_back({line[size_t(side)], line[size_t(s1)], false});
    cut.push_back(cut[size_t(face)]);
    link(partner, 3 * fresh + 1, across_to_third);  // (to -> third)
    link(partner, 3 * face + s1, 3 * fresh + 2);    // (m -> third) against (third -> m)
  }
  // The halves of the copy: f's (u -> m) with g's new (m -> u), and g's (w -> m) with f's new (m -> w).
  link(partner, 3 * f + z, 3 * ng);
  link(partner, 3 * g + y, 3 * nf);
}

/// The sides of edge (a, b), a < b, in face order.
std::vector<int> sides_of(const Result& r, int a, int b) {
  std::vector<int> out;
  for (int f = 0; f < int(r.faces.size()); ++f)
    for (int z = 0; z < 3; ++z) {
      const int u = r.faces[size_t(f)][size_t(z)], w = r.faces[size_t(f)][size_t((z + 1) % 3)];
      if (std::min(u, w) == a && std::max(u, w) == b) out.push_back(3 * f + z);
    }
  return out;
}

}  // namespace

std::vector<std::array<int, 2>> doubled_line_edges(const Result& r) {
  std::vector<std::array<int, 2>> ends;
  for (size_t f = 0; f < r.faces.size(); ++f)
    for (int z = 0; z < 3; ++z)
      if (r.line_edge[f][size_t(z)]) {
        const int u = r.faces[f][size_t(z)], w = r.faces[f][size_t((z + 1) % 3)];
        ends.push_back({std::min(u, w), std::max(u, w)});
      }
  std::sort(ends.begin(), ends.end());
  std::vector<std::array<int, 2>> doubled;
  for (size_t i = 0; i < ends.size();) {
    size_t j = i;
    while (j < ends.size() && ends[j] == ends[i]) ++j;
    if (j - i > 2) doubled.push_back(ends[i]);
    i = j;
  }
  return doubled;
}

int split_doubled_edges(Result& r, std::vector<char>& cut, std::vector<int> partner,
                        const std::vector<std::array<int, 2>>& doubled) {
  int split = 0;
  for (const auto& [a, b] : doubled) {  // few: each looked up in all faces
    const std::vector<int> group = sides_of(r, a, b);
    // The copies: sides paired by `partner`, running opposite ways.
    std::vector<std::pair<int, int>> copies;
    std::vector<char> used(group.size(), 0);
    bool paired = true;
    for (size_t k = 0; k < group.size() && paired; ++k) {
      if (used[k]) continue;
      const int s = group[k], p = partner[size_t(s)];
      const auto at = std::find(group.begin(), group.end(), p);
      const size_t l = size_t(at - group.begin());
      paired = at != group.end() && l != k && !used[l] &&
               r.faces[size_t(s / 3)][size_t(s % 3)] == r.faces[size_t(p / 3)][size_t((p % 3 + 1) % 3)];
      if (paired) {
        used[k] = used[l] = 1;
        copies.push_back({s, p});
      }
    }
    if (!paired) continue;
    for (size_t k = 0; k < copies.size(); ++k) {
      const auto [s, p] = copies[k];
      const auto &pa = r.vertices[size_t(a)], &pb = r.vertices[size_t(b)];
      const int m = int(r.vertices.size());
      r.vertices.push_back({0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1]), 0.5 * (pa[2] + pb[2])});
      split_copy(r, cut, partner, s / 3, s % 3, p / 3, p % 3, m);
    }
    ++split;
  }
  return split;
}

}  // namespace mr::surface_union
