// Which face holds each directed side of the output, kept up through edge swaps: the post-pass
// swaps find the face across an edge, and the fourth point of the pair, through it.
#pragma once

#include "common/flat_index_map.h"
#include "remesh/output_mesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace mr::remesh {

/// Faces f = (x, y, c) and g = (y, x, d) across edge x-y, in their orientation.
struct FacePair {
  int f, g;
  int x, y, c, d;
};

class SideFaces {
public:
  explicit SideFaces(const std::vector<std::array<int, 3>>& faces) {
    face_.reserve(faces.size() * 3);
    for (size_t f = 0; f < faces.size(); ++f)
      for (int z = 0; z < 3; ++z) face_.assign(directed(faces[f][z], faces[f][(z + 1) % 3]), int(f));
  }

  /// The pair across side z of face f, if there is one whose swap to c-d would not repeat an
  /// existing edge.
  bool swappable_pair(const OutputMesh& out, int f, int z, FacePair& p) const {
    const auto& F = out.faces[f];
    p.f = f;
    p.x = F[z], p.y = F[(z + 1) % 3], p.c = F[(z + 2) % 3];
    const int* g = face_.find(directed(p.y, p.x));
    if (!g) return false;
    p.g = *g;
    p.d = -1;
    for (int k : out.faces[p.g]) if (k != p.x && k != p.y) p.d = k;
    return p.d >= 0 && p.d != p.c && !has_edge(p.c, p.d);
  }

  /// Swaps the pair's diagonal x-y to c-d: faces (x, d, c) and (d, y, c).
  void swap(OutputMesh& out, const FacePair& p) {
    set_face(out, p.f, {p.x, p.d, p.c});
    set_face(out, p.g, {p.d, p.y, p.c});
  }

  /// Face f becomes t (a swap, or undoing one).
  void set_face(OutputMesh& out, int f, const std::array<int, 3>& t) {
    auto& F = out.faces[f];
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t side = directed(F[k], F[(k + 1) % 3]);
      const int* g = face_.find(side);
      if (g && *g == f) face_.erase(side);
    }
    F = t;
    for (int k = 0; k < 3; ++k) face_.assign(directed(F[k], F[(k + 1) % 3]), f);
  }

  /// The face holding directed side a->b, or -1.
  int face_of(int a, int b) const {
    const int* f = face_.find(directed(a, b));
    return f ? *f : -1;
  }
  bool has_edge(int a, int b) const { return face_.find(directed(a, b)) || face_.find(directed(b, a)); }

  static std::uint64_t directed(int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); }
  static std::uint64_t undirected(int a, int b) { return a < b ? directed(a, b) : directed(b, a); }

private:
  // directed side -> face: a flat table (the post-pass builds one per sweep of 100k faces and
  // looks up every side; std::unordered_map's node per entry made the lookups and allocations
  // a fifth of the whole remesh of cad/joint.off).
  FlatIndexMap<std::uint64_t> face_;
};

}  // namespace mr::remesh
