#include "common/edge_table.h"

#include <algorithm>

namespace mr {

EdgeTable::EdgeTable(const TriMesh& mesh) {
  build(int(mesh.vert.size()), int(mesh.face.size()),
        [&](int f, int z) { return int(vcg::tri::Index(mesh, mesh.face[f].cV(z))); }, false);
}

EdgeTable::EdgeTable(size_t vertex_count, const std::vector<std::array<int, 3>>& triangles) {
  build(int(vertex_count), int(triangles.size()), [&](int f, int z) { return triangles[f][z]; }, true);
}

template <class VertexOf>
void EdgeTable::build(int nv, int nf, VertexOf index, bool skip_degenerate) {
  // Bucket every face side on its lower vertex (counting sort).
  std::vector<int> bucket_begin(nv + 1, 0);
  auto skipped = [&](int f, int z) { return skip_degenerate && index(f, z) == index(f, (z + 1) % 3); };
  for (int f = 0; f < nf; ++f)
    for (int z = 0; z < 3; ++z)
      if (!skipped(f, z)) ++bucket_begin[std::min(index(f, z), index(f, (z + 1) % 3)) + 1];
  for (int v = 0; v < nv; ++v) bucket_begin[v + 1] += bucket_begin[v];
  struct HalfEdge { int hi; int face; int side; };
  std::vector<HalfEdge> half(bucket_begin[nv]);
  std::vector<int> fill(bucket_begin.begin(), bucket_begin.end() - 1);
  for (int f = 0; f < nf; ++f)
    for (int z = 0; z < 3; ++z) {
      if (skipped(f, z)) continue;
      int a = index(f, z), b = index(f, (z + 1) % 3);
      half[fill[std::min(a, b)]++] = {std::max(a, b), f, z};
    }
  // Within a bucket, group equal upper vertices; the order (face, side) keeps it deterministic.
  face_edge_.assign(3 * size_t(nf), -1);
  sides_.reserve(half.size());
  side_begin_.reserve(half.size() / 2 + 2);
  for (int v = 0; v < nv; ++v) {
    auto first = half.begin() + bucket_begin[v], last = half.begin() + bucket_begin[v + 1];
    std::sort(first, last, [](const HalfEdge& x, const HalfEdge& y) {
      return x.hi != y.hi ? x.hi < y.hi : (x.face != y.face ? x.face < y.face : x.side < y.side);
    });
    for (auto it = first; it != last;) {
      auto run = it;
      int e = int(edge_v0_.size());
      edge_v0_.push_back(v);
      edge_v1_.push_back(it->hi);
      side_begin_.push_back(int(sides_.size()));
      for (; run != last && run->hi == it->hi; ++run) {
        sides_.push_back({run->face, run->side});
        face_edge_[3 * size_t(run->face) + run->side] = e;
      }
      it = run;
    }
  }
  side_begin_.push_back(int(sides_.size()));
}

int EdgeTable::find(int a, int b) const {
  if (a > b) std::swap(a, b);
  int lo = 0, hi = edge_count();
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (edge_v0_[mid] < a || (edge_v0_[mid] == a && edge_v1_[mid] < b)) lo = mid + 1;
    else hi = mid;
  }
  return lo < edge_count() && edge_v0_[lo] == a && edge_v1_[lo] == b ? lo : -1;
}

int EdgeTable::opposite_face(int f, int z) const {
  int e = edge_of(f, z);
  if (valence(e) != 2) return -1;
  FaceSide a = side(e, 0), b = side(e, 1);
  return a.face == f ? b.face : a.face;
}

}  // namespace mr
