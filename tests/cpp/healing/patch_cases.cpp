#include "healing/patch_cases.h"

#include "common/edge_table.h"
#include "shapes.h"

namespace mr::test {

void box_patches(TriMesh& m, std::vector<int>& face_patch, const BoxPatches& spec) {
  std::vector<Point3> points;
  std::vector<std::array<int, 3>> faces;
  face_patch.clear();
  for (int k = 0; k < 6; ++k) {
    const int axis = k % 3;
    const double side = k < 3 ? 1.0 : -1.0;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const int n = spec.resolution[k];
    const int base = int(points.size());
    const double lo = -1 - spec.overlap, hi = 1 + spec.overlap;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        Point3 p;
        p[axis] = side * (1 + spec.offset);
        p[u] = lo + (hi - lo) * i / n;
        p[v] = lo + (hi - lo) * j / n;
        points.push_back(p);
      }
    // (u, v, axis) is right-handed, so counter-clockwise in (u, v) points along +axis.
    const bool reverse = (side < 0) != (k < int(spec.flip.size()) && spec.flip[k]);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = base + j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
        std::array<int, 3> t1 = {a, b, c}, t2 = {a, c, d};
        if (reverse) { std::swap(t1[1], t1[2]); std::swap(t2[1], t2[2]); }
        faces.push_back(t1);
        faces.push_back(t2);
        face_patch.push_back(k);
        face_patch.push_back(k);
      }
  }
  build(m, points, faces);
}

double signed_volume(const TriMesh& m) {
  double v = 0;
  for (const auto& f : m.face) v += f.cP(0) * (f.cP(1) ^ f.cP(2));
  return v / 6;
}

int boundary_edge_count(const TriMesh& m) {
  EdgeTable edges(m);
  int n = 0;
  for (int e = 0; e < edges.edge_count(); ++e) n += edges.valence(e) == 1;
  return n;
}

int non_manifold_edge_count(const TriMesh& m) {
  EdgeTable edges(m);
  int n = 0;
  for (int e = 0; e < edges.edge_count(); ++e) n += edges.valence(e) > 2;
  return n;
}

bool consistently_oriented(const TriMesh& m) {
  EdgeTable edges(m);
  for (int e = 0; e < edges.edge_count(); ++e) {
    if (edges.valence(e) != 2) continue;
    const FaceSide a = edges.side(e, 0), b = edges.side(e, 1);
    if (m.face[a.face].cV(a.side) == m.face[b.face].cV(b.side)) return false;
  }
  return true;
}

}  // namespace mr::test
