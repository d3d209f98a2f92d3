#include "healing/seam_welding.h"

#include <algorithm>

namespace mr::healing {

Welded weld_classes(const Soup& s, const std::vector<int>& weld_class) {
  Welded out;
  const int n = int(s.pos.size());
  // Mean as representative + mean offset, so coincident members stay bit-exact.
  std::vector<Point3> sum(n, Point3(0, 0, 0));
  std::vector<int> count(n, 0);
  for (int v = 0; v < n; ++v) { sum[weld_class[v]] += s.pos[v] - s.pos[weld_class[v]]; ++count[weld_class[v]]; }

  std::vector<char> used(n, 0);
  std::vector<std::array<int, 3>> tris;
  std::vector<int> patches;
  std::vector<std::array<int, 3>> seen;  // sorted vertex triples, for duplicates
  for (size_t f = 0; f < s.tri.size(); ++f) {
    std::array<int, 3> t = {weld_class[s.tri[f][0]], weld_class[s.tri[f][1]], weld_class[s.tri[f][2]]};
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) { ++out.degenerate_faces_removed; continue; }
    tris.push_back(t);
    patches.push_back(s.patch[f]);
  }
  // Drop a face whose three vertices another earlier face already has; only
  // faces with a welded vertex can have become duplicates.
  std::vector<char> welded(n, 0);
  for (int v = 0; v < n; ++v)
    if (weld_class[v] != v) welded[v] = welded[weld_class[v]] = 1;
  std::vector<std::pair<std::array<int, 3>, int>> order;
  for (size_t f = 0; f < tris.size(); ++f) {
    if (!(welded[tris[f][0]] || welded[tris[f][1]] || welded[tris[f][2]])) continue;
    auto key = tris[f];
    std::sort(key.begin(), key.end());
    order.push_back({key, int(f)});
  }
  std::sort(order.begin(), order.end());
  std::vector<char> keep(tris.size(), 1);
  for (size_t i = 1; i < order.size(); ++i)
    if (order[i].first == order[i - 1].first) { keep[order[i].second] = 0; ++out.duplicate_faces_removed; }

  for (size_t f = 0; f < tris.size(); ++f)
    if (keep[f]) for (int v : tris[f]) used[v] = 1;
  out.new_index.assign(n, -1);
  for (int v = 0; v < n; ++v)
    if (used[v]) {
      out.new_index[v] = int(out.soup.pos.size());
      const Point3 mean = s.pos[v] + sum[v] / double(count[v]);
      out.soup.pos.push_back(mean);
    }
  out.move.assign(out.soup.pos.size(), 0.0);
  for (int v = 0; v < n; ++v) {
    const int w = out.new_index[weld_class[v]];
    if (w < 0) continue;
    out.move[w] = std::max(out.move[w], vcg::Distance(s.pos[v], out.soup.pos[w]));
  }
  for (int v = 0; v < n; ++v)
    if (weld_class[v] != v && out.new_index[weld_class[v]] >= 0) out.new_index[v] = out.new_index[weld_class[v]];
  for (size_t f = 0; f < tris.size(); ++f) {
    if (!keep[f]) continue;
    out.soup.tri.push_back({out.new_index[tris[f][0]], out.new_index[tris[f][1]], out.new_index[tris[f][2]]});
    out.soup.patch.push_back(patches[f]);
  }
  return out;
}

}  // namespace mr::healing
