#include "union/self_intersection.h"

#include "union/exact.h"
#include "union/face_clearance.h"
#include "union/triangle_angles.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mr::surface_union {

namespace {
// Up to this many faces a sweep along x finds the pairs with overlapping boxes at less
// cost than the grid (a body of a sphere cluster, a blob); beyond, it would compare
// each face with a slab of the body.
constexpr int kSweepUpTo = 4096;

int find(std::vector<int>& uf, int x) {
  while (uf[size_t(x)] != x) x = uf[size_t(x)] = uf[size_t(uf[size_t(x)])];
  return x;
}

/// One edge-connected piece whose edges all turn the same way (convex, or flat; exact)
/// and whose vertices have face angles summing to at most 2 pi: a closed surface that is
/// locally convex everywhere bounds a convex body (Van Heijenoort 1952), so it cannot
/// cross itself. Sphere-cluster bodies and CAD plates are such. The angle sums are
/// doubles: a vertex within 1e-9 of 2 pi counts as flat.
bool locally_convex(const Body& b) {
  const int nf = int(b.faces.size());
  std::vector<std::array<int, 3>> half;  // (low vertex, high vertex, 3 * face + side)
  half.reserve(3 * size_t(nf));
  for (int f = 0; f < nf; ++f)
    for (int z = 0; z < 3; ++z) {
      const int u = b.faces[size_t(f)][size_t(z)], w = b.faces[size_t(f)][size_t((z + 1) % 3)];
      half.push_back({std::min(u, w), std::max(u, w), 3 * f + z});
    }
  std::sort(half.begin(), half.end());
  std::vector<int> uf(static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f) uf[size_t(f)] = f;
  int turn = 0;  // the sign every edge's turn must have
  for (size_t i = 0; i + 1 < half.size(); i += 2) {
    if (half[i][0] != half[i + 1][0] || half[i][1] != half[i + 1][1]) return false;  // (validated: two per edge)
    const int f = half[i][2] / 3, z = half[i][2] % 3, g = half[i + 1][2] / 3, y = half[i + 1][2] % 3;
    uf[size_t(find(uf, f))] = find(uf, g);
    const auto& t = b.faces[size_t(f)];
    const int d = b.faces[size_t(g)][size_t((y + 2) % 3)];
    const int o = orient3d(b.vertices[size_t(t[size_t(z)])].data(), b.vertices[size_t(t[size_t((z + 1) % 3)])].data(),
                           b.vertices[size_t(t[size_t((z + 2) % 3)])].data(), b.vertices[size_t(d)].data());
    if (o != 0) {
      if (turn != 0 && o != turn) return false;
      turn = o;
    }
  }
  for (int f = 1; f < nf; ++f)
    if (find(uf, f) != find(uf, 0)) return false;
  std::vector<double> angle(b.vertices.size(), 0);
  for (const auto& t : b.faces)
    for (int z = 0; z < 3; ++z)
      angle[size_t(t[size_t(z)])] += corner_angle(b.vertices[size_t(t[size_t(z)])], b.vertices[size_t(t[size_t((z + 1) % 3)])],
                                                  b.vertices[size_t(t[size_t((z + 2) % 3)])]);
  for (double a : angle)
    if (a > 2 * 3.14159265358979323846 + 1e-9) return false;
  return true;
}
}  // namespace

std::optional<std::array<int, 2>> self_intersection(const Body& b) {
  const int nf = int(b.faces.size());
  if (nf < 2 || locally_convex(b)) return std::nullopt;
  std::vector<std::array<V3, 2>> box(static_cast<size_t>(nf));
  V3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  double mean = 0;
  for (int f = 0; f < nf; ++f) {
    auto& [a, c] = box[size_t(f)];
    a = c = b.vertices[size_t(b.faces[size_t(f)][0])];
    for (int z = 1; z < 3; ++z)
      for (int k = 0; k < 3; ++k) {
        a[k] = std::min(a[k], b.vertices[size_t(b.faces[size_t(f)][size_t(z)])][k]);
        c[k] = std::max(c[k], b.vertices[size_t(b.faces[size_t(f)][size_t(z)])][k]);
      }
    for (int k = 0; k < 3; ++k) { lo[k] = std::min(lo[k], a[k]); hi[k] = std::max(hi[k], c[k]); }
    mean += std::max({c[0] - a[0], c[1] - a[1], c[2] - a[2]});
  }
  mean /= nf;
  // Faces f and g with overlapping boxes: do they cross?
  auto cross = [&](int f, int g) {
    const auto &bf = box[size_t(f)], &bg = box[size_t(g)];
    for (int c = 0; c < 3; ++c)
      if (bf[1][c] < bg[0][c] || bg[1][c] < bf[0][c]) return false;
    const auto &tf = b.faces[size_t(f)], &tg = b.faces[size_t(g)];
    int shared = 0;  // neighbours across an edge meet only along it
    for (int x : tf) shared += x == tg[0] || x == tg[1] || x == tg[2];
    if (shared >= 2) return false;
    const V3 pf[3] = {b.vertices[size_t(tf[0])], b.vertices[size_t(tf[1])], b.vertices[size_t(tf[2])]};
    const V3 pg[3] = {b.vertices[size_t(tg[0])], b.vertices[size_t(tg[1])], b.vertices[size_t(tg[2])]};
    return triangles_meet(tf, pf, tg, pg);
  };
  if (nf <= kSweepUpTo) {
    // Few faces: sorted by the low end of their boxes along x, each against those that
    // start before it ends.
    std::vector<int> order(static_cast<size_t>(nf));
    for (int f = 0; f < nf; ++f) order[size_t(f)] = f;
    std::sort(order.begin(), order.end(), [&](int f, int g) {
      return box[size_t(f)][0][0] < box[size_t(g)][0][0] || (box[size_t(f)][0][0] == box[size_t(g)][0][0] && f < g);
    });
    for (size_t i = 0; i < order.size(); ++i)
      for (size_t j = i + 1; j < order.size() && box[size_t(order[j])][0][0] <= box[size_t(order[i])][1][0]; ++j)
        if (cross(order[i], order[j]))
          return std::array<int, 2>{std::min(order[i], order[j]), std::max(order[i], order[j])};
    return std::nullopt;
  }
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  // Cells about twice the mean face (a face then covers a few), at most 1024 per axis.
  double cell = std::max(2 * mean, extent / 1024);
  if (!(cell > 0)) cell = 1;
  auto cell_of = [&](double x, int k) { return int64_t(std::floor((x - lo[k]) / cell)); };
  auto key = [](int64_t i, int64_t j, int64_t k) { return (i * 1031 + j) * 1031 + k; };
  // (cell, face) for every cell a face's box covers, sorted: each cell's faces in a run.
  std::vector<std::pair<int64_t, int>> filed;
  filed.reserve(size_t(nf) * 2);
  for (int f = 0; f < nf; ++f) {
    const auto& [a, c] = box[size_t(f)];
    for (int64_t i = cell_of(a[0], 0); i <= cell_of(c[0], 0); ++i)
      for (int64_t j = cell_of(a[1], 1); j <= cell_of(c[1], 1); ++j)
        for (int64_t k = cell_of(a[2], 2); k <= cell_of(c[2], 2); ++k) filed.push_back({key(i, j, k), f});
  }
  std::sort(filed.begin(), filed.end());
  // Each face against the later faces of the cells it covers; a stamp per face keeps a
  // pair from being tested twice (no per-pair cell arithmetic).
  std::vector<int> seen(static_cast<size_t>(nf), -1);
  for (int f = 0; f < nf; ++f) {
    const auto& bf = box[size_t(f)];
    for (int64_t i = cell_of(bf[0][0], 0); i <= cell_of(bf[1][0], 0); ++i)
      for (int64_t j = cell_of(bf[0][1], 1); j <= cell_of(bf[1][1], 1); ++j)
        for (int64_t k = cell_of(bf[0][2], 2); k <= cell_of(bf[1][2], 2); ++k) {
          const int64_t here = key(i, j, k);
          auto it = std::lower_bound(filed.begin(), filed.end(), std::pair<int64_t, int>{here, f + 1});
          for (; it != filed.end() && it->first == here; ++it) {
            const int g = it->second;  // g > f
            if (seen[size_t(g)] == f) continue;
            seen[size_t(g)] = f;
            if (cross(f, g)) return std::array<int, 2>{f, g};
          }
        }
  }
  return std::nullopt;
}

}  // namespace mr::surface_union
