#include "common/coherent_orientation.h"

#include "common/edge_table.h"

#include <utility>
#include <vector>

namespace mr {

namespace {

int vertex(const TriMesh& mesh, int f, int z) { return int(vcg::tri::Index(mesh, mesh.face[f].cV(z % 3))); }

// Do faces a and b, on manifold edge e, run it the same way?
bool same_direction(const TriMesh& mesh, const EdgeTable& edges, int e) {
  const FaceSide a = edges.side(e, 0), b = edges.side(e, 1);
  return vertex(mesh, a.face, a.side) == vertex(mesh, b.face, b.side);
}

}  // namespace

int count_misoriented_edges(const TriMesh& mesh) {
  const EdgeTable edges(mesh);
  int n = 0;
  for (int e = 0; e < edges.edge_count(); ++e)
    if (edges.valence(e) == 2 && same_direction(mesh, edges, e)) ++n;
  return n;
}

CoherentOrientation orient_coherently(TriMesh& mesh) {
  const EdgeTable edges(mesh);
  const int nf = int(mesh.face.size());
  std::vector<signed char> flip(nf, -1);  // -1: not reached yet
  CoherentOrientation result;
  std::vector<int> part, stack;
  for (int seed = 0; seed < nf; ++seed) {
    if (flip[seed] >= 0) continue;
    part.clear();
    flip[seed] = 0;
    stack.push_back(seed);
    double kept_area = 0, flipped_area = 0;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      part.push_back(f);
      (flip[f] ? flipped_area : kept_area) += vcg::DoubleArea(mesh.face[f]);
      for (int z = 0; z < 3; ++z) {
        const int e = edges.edge_of(f, z);
        if (e < 0 || edges.valence(e) != 2) continue;
        const int g = edges.opposite_face(f, z);
        // g must be flipped relative to f exactly when they run the edge the same way.
        const signed char want = static_cast<signed char>(flip[f] ^ (same_direction(mesh, edges, e) ? 1 : 0));
        if (flip[g] < 0) {
          flip[g] = want;
          stack.push_back(g);
        } else if (flip[g] != want && f < g) {
          ++result.conflicts;
        }
      }
    }
    // The part keeps the orientation of the larger area.
    if (flipped_area > kept_area)
      for (int f : part) flip[f] = static_cast<signed char>(1 - flip[f]);
  }
  for (int f = 0; f < nf; ++f) {
    if (!flip[f]) continue;
    auto& t = mesh.face[f];
    auto* v1 = t.V(1);
    t.V(1) = t.V(2);
    t.V(2) = v1;
    // Sides 0 (V0 V1) and 2 (V2 V0) trade places; side 1 stays: so do their edge flags.
    const bool s0 = t.IsFaceEdgeS(0), s2 = t.IsFaceEdgeS(2), f0 = t.IsF(0), f2 = t.IsF(2);
    s2 ? t.SetFaceEdgeS(0) : t.ClearFaceEdgeS(0);
    s0 ? t.SetFaceEdgeS(2) : t.ClearFaceEdgeS(2);
    f2 ? t.SetF(0) : t.ClearF(0);
    f0 ? t.SetF(2) : t.ClearF(2);
    ++result.flipped;
  }
  return result;
}

}  // namespace mr
