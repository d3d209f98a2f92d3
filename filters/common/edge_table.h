// Undirected edges of a triangle mesh with every incident face side, built in
// O(N) by bucketing half-edges on their lower vertex. Unlike VCG's FF adjacency
// it represents non-manifold edges (three or more faces) explicitly.
#pragma once

#include "common/tri_mesh.h"

#include <array>
#include <cstdint>
#include <vector>

namespace mr {

struct FaceSide {
  int face;  ///< face index
  int side;  ///< 0..2: the side from corner `side` to corner `(side+1)%3`
};

class EdgeTable {
public:
  explicit EdgeTable(const TriMesh& mesh);
  /// From indexed triangles. Degenerate sides (both ends one vertex, as welding leaves them) get
  /// no edge: edge_of is -1 there.
  EdgeTable(size_t vertex_count, const std::vector<std::array<int, 3>>& triangles);

  int edge_count() const { return int(edge_v0_.size()); }
  int v0(int e) const { return edge_v0_[e]; }  ///< lower vertex index
  int v1(int e) const { return edge_v1_[e]; }  ///< higher vertex index
  struct Ends { int v0, v1; };
  Ends ends(int e) const { return {edge_v0_[e], edge_v1_[e]}; }
  /// Number of face sides on edge e (1 = boundary, 2 = manifold, >2 = non-manifold).
  int valence(int e) const { return side_begin_[e + 1] - side_begin_[e]; }
  FaceSide side(int e, int k) const { return sides_[side_begin_[e] + k]; }
  /// Edge index of face f's side z.
  int edge_of(int f, int z) const { return face_edge_[3 * f + z]; }
  /// The other face across a manifold edge, or -1.
  int opposite_face(int f, int z) const;
  /// Index of edge (a,b) in either order, or -1 (binary search: edges are sorted by (v0, v1)).
  int find(int a, int b) const;

private:
  template <class VertexOf>
  void build(int vertex_count, int face_count, VertexOf vertex_of, bool skip_degenerate);

  std::vector<int> edge_v0_, edge_v1_;
  std::vector<int> side_begin_;
  std::vector<FaceSide> sides_;
  std::vector<int> face_edge_;
};

}  // namespace mr
