// The live faces around each output point, kept up through edge collapses: the bookkeeping the
// post-pass's collapses share (free points at short edges, line points whose segments merge).
#pragma once

#include "remesh/output_mesh.h"

#include <algorithm>
#include <vector>

namespace mr::remesh {

class PointStars {
public:
  explicit PointStars(const OutputMesh& out);

  const std::vector<int>& of(int v) const { return star_[size_t(v)]; }
  std::vector<int>& of(int v) { return star_[size_t(v)]; }
  /// Room for a point added after construction.
  void add_point() { star_.emplace_back(); }
  /// Face f no longer has v as a corner (a split or a flip gave it another).
  void drop_face(int v, int f) {
    auto& star = star_[size_t(v)];
    star.erase(std::remove(star.begin(), star.end(), f), star.end());
  }

  /// v's neighbours, sorted.
  std::vector<int> neighbours(const OutputMesh& out, int v) const;
  /// The faces holding both v and w.
  std::vector<int> faces_on(const OutputMesh& out, int v, int w) const;
  /// Collapsing v onto w keeps the surface a manifold: v and w share no neighbour but the
  /// third points of `dying`, the faces on edge v-w.
  bool link_condition(const OutputMesh& out, int v, int w, const std::vector<int>& dying) const;
  /// Collapses v onto w: the faces `dying` are marked dead ({-1, -1, -1}), v's other faces
  /// take w, and the stars follow. drop_dead_faces() removes the dead ones later.
  void collapse(OutputMesh& out, int v, int w, const std::vector<int>& dying);

private:
  std::vector<std::vector<int>> star_;
};

/// Removes the faces a collapse marked dead, keeping the others' order and patches.
void drop_dead_faces(OutputMesh& out);

}  // namespace mr::remesh
