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
// cost than the grid (rabbit.obj's blobs); beyond, each face meets a growing slab of the
// body (ballA.off's 3796 faces: 34M instructions swept, 17M on the grid).
constexpr int kSweepUpTo = 512;

int find(std::vector<int>& uf, int x) {
  while (uf[size_t(x)] != x) x = uf[size_t(x)] = uf[size_t(uf[size_t(x)])];
  return x;
}

/// Where the surface is locally convex. A vertex is when every edge at it is convex or
/// flat (exact) and its face angles sum to at most 2 pi (doubles: within 1e-9 counts as
/// flat): two faces at such a vertex lie on a convex cone there and meet only at it or
/// along an edge. A body that is one piece and convex at every vertex bounds a convex
/// body (a closed, locally convex surface: Van Heijenoort 1952) and cannot cross itself.
struct Convexity {
  std::vector<char> vertex;  // per vertex
  bool whole = false;
};

Convexity convexity(const Body& b) {
  const int nf = int(b.faces.size()), nv = int(b.vertices.size());
  Convexity out;
  out.vertex.assign(size_t(nv), 1);
  // Sides bucketed by their lower vertex (a counting sort), then by the higher one.
  std::vector<int> begin(size_t(nv) + 1, 0);
  auto low = [&](int side) {
    const auto& t = b.faces[size_t(side / 3)];
    return std::min(t[size_t(side % 3)], t[size_t((side % 3 + 1) % 3)]);
  };
  auto high = [&](int side) {
    const auto& t = b.faces[size_t(side / 3)];
    return std::max(t[size_t(side % 3)], t[size_t((side % 3 + 1) % 3)]);
  };
  for (int s = 0; s < 3 * nf; ++s) ++begin[size_t(low(s)) + 1];
  for (int v = 0; v < nv; ++v) begin[size_t(v) + 1] += begin[size_t(v)];
  std::vector<int> sides(size_t(3) * size_t(nf));
  {
    std::vector<int> next(begin.begin(), begin.end() - 1);
    for (int s = 0; s < 3 * nf; ++s) sides[size_t(next[size_t(low(s))]++)] = s;
  }
  for (int v = 0; v < nv; ++v) {  // a vertex's few edges: insertion, but for a fan's apex
    const auto first = sides.begin() + begin[size_t(v)], last = sides.begin() + begin[size_t(v) + 1];
    auto by_high = [&](int x, int y) { return high(x) < high(y); };
    if (last - first > 32) std::stable_sort(first, last, by_high);
    else
      for (auto i = first + (first != last); i < last; ++i)
        for (auto j = i; j > first && by_high(*j, *(j - 1)); --j) std::iter_swap(j - 1, j);
  }
  // Outward or inward (validation turns inward bodies over afterwards): a convex edge
  // has its neighbour's third corner below the face's plane, seen from outside.
  double volume = 0;
  for (const auto& t : b.faces) {
    const auto &p = b.vertices[size_t(t[0])], &q = b.vertices[size_t(t[1])], &r = b.vertices[size_t(t[2])];
    volume += p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) + p[2] * (q[0] * r[1] - q[1] * r[0]);
  }
  const int reflex = volume >= 0 ? 1 : -1;
  std::vector<int> uf(static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f) uf[size_t(f)] = f;
  for (size_t i = 0; i + 1 < sides.size(); i += 2) {
    const int s = sides[i], o = sides[i + 1];
    if (low(s) != low(o) || high(s) != high(o)) return out;  // not two sides per edge (validated before)
    const int f = s / 3, z = s % 3;
    uf[size_t(find(uf, f))] = find(uf, o / 3);
    const auto& t = b.faces[size_t(f)];
    const int d = b.faces[size_t(o / 3)][size_t((o % 3 + 2) % 3)];
    if (orient3d(b.vertices[size_t(t[size_t(z)])].data(), b.vertices[size_t(t[size_t((z + 1) % 3)])].data(),
                 b.vertices[size_t(t[size_t((z + 2) % 3)])].data(), b.vertices[size_t(d)].data()) == reflex)
      out.vertex[size_t(low(s))] = out.vertex[size_t(high(s))] = 0;
  }
  std::vector<double> angle(size_t(nv), 0);
  for (const auto& t : b.faces)
    for (int z = 0; z < 3; ++z)
      if (out.vertex[size_t(t[size_t(z)])])  // (reflex already: its angles do not matter)
        angle[size_t(t[size_t(z)])] += corner_angle(b.vertices[size_t(t[size_t(z)])],
                                                  b.vertices[size_t(t[size_t((z + 1) % 3)])],
                                                  b.vertices[size_t(t[size_t((z + 2) % 3)])]);
  for (int v = 0; v < nv; ++v)
    if (angle[size_t(v)] > 2 * 3.14159265358979323846 + 1e-9) out.vertex[size_t(v)] = 0;
  out.whole = std::all_of(out.vertex.begin(), out.vertex.end(), [](char c) { return c != 0; });
  for (int f = 1; f < nf && out.whole; ++f) out.whole = find(uf, f) == find(uf, 0);
  return out;
}

}  // namespace

std::optional<std::array<int, 2>> self_intersection(const Body& b) {
  const int nf = int(b.faces.size());
  if (nf < 2) return std::nullopt;
  const Convexity convex = convexity(b);
  if (convex.whole) return std::nullopt;
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
    int shared = 0, at = -1;
    for (int x : tf)
      if (x == tg[0] || x == tg[1] || x == tg[2]) { ++shared; at = x; }
    if (shared >= 2) return false;                              // neighbours across an edge meet only along it
    if (shared == 1 && convex.vertex[size_t(at)]) return false;  // on a convex cone at their corner
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
  // pair from being tested twice.
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
