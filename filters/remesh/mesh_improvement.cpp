#include "remesh/mesh_improvement.h"

#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>

namespace mr::remesh {

namespace {

std::uint64_t directed(int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); }
std::uint64_t undirected(int a, int b) { return directed(std::min(a, b), std::max(a, b)); }

double face_min_angle(const OutputMesh& out, const std::array<int, 3>& f) {
  return min_angle(out.points[f[0]], out.points[f[1]], out.points[f[2]]);
}

int swap_pass(OutputMesh& out, const std::unordered_set<std::uint64_t>& fixed) {
  std::unordered_map<std::uint64_t, int> side_face;  // directed side -> face
  side_face.reserve(out.faces.size() * 3);
  for (size_t f = 0; f < out.faces.size(); ++f)
    for (int z = 0; z < 3; ++z) side_face[directed(out.faces[f][z], out.faces[f][(z + 1) % 3])] = int(f);
  int swaps = 0;
  for (size_t fi = 0; fi < out.faces.size(); ++fi) {
    for (int z = 0; z < 3; ++z) {
      const auto F = out.faces[fi];
      const int x = F[z], y = F[(z + 1) % 3], c = F[(z + 2) % 3];
      if (fixed.count(undirected(x, y))) continue;
      auto it = side_face.find(directed(y, x));
      if (it == side_face.end()) continue;
      const int gi = it->second;
      if (out.face_patch[gi] != out.face_patch[fi]) continue;
      const auto G = out.faces[gi];
      int d = -1;
      for (int k = 0; k < 3; ++k) if (G[k] != x && G[k] != y) d = G[k];
      if (d < 0 || d == c) continue;
      if (side_face.count(directed(c, d)) || side_face.count(directed(d, c))) continue;
      const Point3 nf = unit_normal(out.points[x], out.points[y], out.points[c]);
      const Point3 ng = unit_normal(out.points[y], out.points[x], out.points[d]);
      if (nf * ng < 0.9) continue;  // keep the surface shape: swap only nearly flat pairs
      Point3 n = nf + ng;
      n.Normalize();
      const std::array<int, 3> A = {x, d, c}, B = {d, y, c};
      const Point3 na = unit_normal(out.points[x], out.points[d], out.points[c]);
      const Point3 nb = unit_normal(out.points[d], out.points[y], out.points[c]);
      if (na * n < 0.9 || nb * n < 0.9) continue;
      const double before = std::min(face_min_angle(out, F), face_min_angle(out, G));
      const double after = std::min(face_min_angle(out, A), face_min_angle(out, B));
      if (after <= before + 1e-6) continue;
      for (int k = 0; k < 3; ++k) {
        side_face.erase(directed(F[k], F[(k + 1) % 3]));
        side_face.erase(directed(G[k], G[(k + 1) % 3]));
      }
      out.faces[fi] = A;
      out.faces[gi] = B;
      for (int k = 0; k < 3; ++k) {
        side_face[directed(A[k], A[(k + 1) % 3])] = int(fi);
        side_face[directed(B[k], B[(k + 1) % 3])] = gi;
      }
      ++swaps;
    }
  }
  return swaps;
}

int smooth_pass(OutputMesh& out, const SurfaceLocator& locator) {
  const size_t nv = out.points.size();
  std::vector<int> begin(nv + 1, 0), ring;
  for (const auto& f : out.faces) for (int v : f) begin[v + 1]++;
  for (size_t i = 1; i <= nv; ++i) begin[i] += begin[i - 1];
  ring.resize(begin[nv]);
  std::vector<int> fill(begin.begin(), begin.end() - 1);
  for (size_t f = 0; f < out.faces.size(); ++f) for (int v : out.faces[f]) ring[fill[v]++] = int(f);
  const Surface& s = locator.surface();
  int moves = 0;
  for (size_t v = 0; v < nv; ++v) {
    if (out.kind[v] != PointKind::Free || begin[v] == begin[v + 1]) continue;
    const int patch = out.face_patch[ring[begin[v]]];
    Point3 centre(0, 0, 0);
    int count = 0;
    double before = 1e9;
    for (int k = begin[v]; k < begin[v + 1]; ++k) {
      const auto& f = out.faces[ring[k]];
      before = std::min(before, face_min_angle(out, f));
      for (int u : f) if (u != int(v)) { centre += out.points[u]; ++count; }
    }
    centre /= double(count);
    const Point3 normal = out.host[v] >= 0 ? s.face_normal[out.host[v]] : Point3(0, 0, 0);
    const Projection pr = locator.locate(centre, patch, normal, out.host[v], (centre - out.points[v]).Norm() * 2 + 1e-12);
    if (pr.face < 0) continue;
    const Point3 old = out.points[v];
    out.points[v] = pr.point;
    double after = 1e9;
    bool folded = false;
    for (int k = begin[v]; k < begin[v + 1]; ++k) {
      const auto& f = out.faces[ring[k]];
      after = std::min(after, face_min_angle(out, f));
      if (unit_normal(out.points[f[0]], out.points[f[1]], out.points[f[2]]) * s.face_normal[pr.face] < 0.5) folded = true;
    }
    if (folded || after <= before + 1e-9) { out.points[v] = old; continue; }
    out.host[v] = pr.face;
    ++moves;
  }
  return moves;
}

}  // namespace

ImprovementResult improve_mesh(OutputMesh& out, const std::vector<std::array<int, 2>>& feature_edges,
                               const SurfaceLocator& locator, int iterations) {
  std::unordered_set<std::uint64_t> fixed;
  for (const auto& e : feature_edges) fixed.insert(undirected(e[0], e[1]));
  ImprovementResult r;
  for (int it = 0; it < iterations; ++it) {
    const int swaps = swap_pass(out, fixed);
    const int moves = smooth_pass(out, locator);
    r.swaps += swaps;
    r.moves += moves;
    if (swaps == 0 && moves == 0) break;
  }
  return r;
}

}  // namespace mr::remesh
