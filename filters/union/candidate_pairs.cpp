#include "union/candidate_pairs.h"

#include "common/parallel_for.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace mr::surface_union {

namespace {

struct Box {
  double lo[3], hi[3];
  bool overlaps(const Box& o) const {
    for (int k = 0; k < 3; ++k)
      if (hi[k] < o.lo[k] || o.hi[k] < lo[k]) return false;
    return true;
  }
};

Box face_box(const Soup& s, int f) {
  Box b;
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = b.hi[k] = s.vertex[s.face[f][0]][k];
    for (int c = 1; c < 3; ++c) {
      b.lo[k] = std::min(b.lo[k], s.vertex[s.face[f][c]][k]);
      b.hi[k] = std::max(b.hi[k], s.vertex[s.face[f][c]][k]);
    }
  }
  return b;
}

}  // namespace

std::vector<std::pair<int, int>> candidate_pairs(const Soup& s) {
  const int nf = int(s.face.size());
  std::vector<Box> box(nf);
  std::vector<Box> body_box(s.body_count);
  std::vector<bool> body_seen(s.body_count, false);
  for (int f = 0; f < nf; ++f) {
    box[f] = face_box(s, f);
    Box& bb = body_box[s.body[f]];
    if (!body_seen[s.body[f]]) { bb = box[f]; body_seen[s.body[f]] = true; }
    for (int k = 0; k < 3; ++k) { bb.lo[k] = std::min(bb.lo[k], box[f].lo[k]); bb.hi[k] = std::max(bb.hi[k], box[f].hi[k]); }
  }
  // Only faces that overlap another body's box can intersect anything.
  std::vector<int> active;
  {
    // Sweep over bodies is quadratic in the body count only; fine for thousands.
    std::vector<std::vector<int>> others(s.body_count);
    for (int a = 0; a < s.body_count; ++a)
      for (int b = 0; b < s.body_count; ++b)
        if (a != b && body_seen[a] && body_seen[b] && body_box[a].overlaps(body_box[b])) others[a].push_back(b);
    for (int f = 0; f < nf; ++f)
      for (int b : others[s.body[f]])
        if (box[f].overlaps(body_box[b])) { active.push_back(f); break; }
  }
  std::vector<std::pair<int, int>> pairs;
  if (active.empty()) return pairs;
  Box all = box[active[0]];
  double mean = 0;
  for (int f : active) {
    for (int k = 0; k < 3; ++k) { all.lo[k] = std::min(all.lo[k], box[f].lo[k]); all.hi[k] = std::max(all.hi[k], box[f].hi[k]); }
    mean += std::max({box[f].hi[0] - box[f].lo[0], box[f].hi[1] - box[f].lo[1], box[f].hi[2] - box[f].lo[2]});
  }
  mean /= double(active.size());
  double extent = std::max({all.hi[0] - all.lo[0], all.hi[1] - all.lo[1], all.hi[2] - all.lo[2]});
  // Cells about twice the mean face size, at most ~128^3 per axis product.
  double cell = std::max(2.0 * mean, extent / 256.0);
  if (!(cell > 0)) cell = 1.0;
  int dim[3];
  for (int k = 0; k < 3; ++k) dim[k] = std::max(1, int(std::floor((all.hi[k] - all.lo[k]) / cell)) + 1);
  auto cell_of = [&](double v, int k) { return std::clamp(int(std::floor((v - all.lo[k]) / cell)), 0, dim[k] - 1); };
  std::unordered_map<int64_t, std::vector<int>> grid;
  grid.reserve(active.size() * 2);
  auto key = [&](int i, int j, int k) { return (int64_t(i) * dim[1] + j) * dim[2] + k; };
  for (int f : active) {
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k) { lo[k] = cell_of(box[f].lo[k], k); hi[k] = cell_of(box[f].hi[k], k); }
    for (int i = lo[0]; i <= hi[0]; ++i)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int k = lo[2]; k <= hi[2]; ++k) grid[key(i, j, k)].push_back(f);
  }
  // The cells are independent: their pairs are found in parallel, per chunk of cells,
  // and sorted together (the result does not depend on the order they were found in).
  std::vector<const std::pair<const int64_t, std::vector<int>>*> cells;
  cells.reserve(grid.size());
  for (const auto& entry : grid) cells.push_back(&entry);
  constexpr size_t kCellsPerChunk = 256;
  std::vector<std::vector<std::pair<int, int>>> found((cells.size() + kCellsPerChunk - 1) / kCellsPerChunk);
  parallel_for(found.size(), 1, [&](size_t chunk) {
    for (size_t n = chunk * kCellsPerChunk, end = std::min(cells.size(), n + kCellsPerChunk); n < end; ++n) {
      const int64_t cell_key = cells[n]->first;
      const std::vector<int>& faces = cells[n]->second;
      for (size_t x = 0; x < faces.size(); ++x)
        for (size_t y = x + 1; y < faces.size(); ++y) {
          const int f = faces[x], g = faces[y];
          if (s.body[f] == s.body[g] || !box[f].overlaps(box[g])) continue;
          // Report the pair only in the cell holding the low corner of the boxes' overlap.
          int c[3];
          for (int k = 0; k < 3; ++k) c[k] = cell_of(std::max(box[f].lo[k], box[g].lo[k]), k);
          if (key(c[0], c[1], c[2]) != cell_key) continue;
          found[chunk].emplace_back(std::min(f, g), std::max(f, g));
        }
    }
  });
  size_t total = 0;
  for (const auto& f : found) total += f.size();
  pairs.reserve(total);
  for (auto& f : found) {
    pairs.insert(pairs.end(), f.begin(), f.end());
    std::vector<std::pair<int, int>>().swap(f);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace mr::surface_union
