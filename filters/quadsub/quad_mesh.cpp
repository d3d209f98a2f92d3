#include "quadsub/quad_mesh.h"

#include "common/edge_table.h"
#include "common/errors.h"

#include <map>
#include <set>

namespace mr::quadsub {

std::vector<std::vector<int>> polygons_from_faux_edges(const TriMesh& mesh, std::vector<int>* polygon_of_face) {
  const int nf = int(mesh.face.size());
  const EdgeTable edges(mesh);
  auto vid = [&](int f, int z) { return int(vcg::tri::Index(mesh, mesh.face[f].cV(z))); };
  std::vector<int> region(nf, -1);
  std::vector<std::vector<int>> polygons;
  std::vector<int> stack, members;
  for (int seed = 0; seed < nf; ++seed) {
    if (region[seed] >= 0) continue;
    const int id = int(polygons.size());
    members.clear();
    region[seed] = id;
    stack.push_back(seed);
    while (!stack.empty()) {
      int f = stack.back();
      stack.pop_back();
      members.push_back(f);
      for (int z = 0; z < 3; ++z) {
        if (!mesh.face[f].IsF(z)) continue;
        int g = edges.opposite_face(f, z);
        if (g >= 0 && region[g] < 0) { region[g] = id; stack.push_back(g); }
      }
    }
    // The polygon's border: the non-faux sides, chained tail to head.
    std::map<int, int> next;
    for (int f : members)
      for (int z = 0; z < 3; ++z)
        if (!mesh.face[f].IsF(z) || edges.opposite_face(f, z) < 0 ||
            region[edges.opposite_face(f, z)] != id) {
          if (!next.emplace(vid(f, z), vid(f, (z + 1) % 3)).second)
            throw InvalidInput("a polygon (faces joined by faux edges) touches itself at a vertex: "
                               "split it or clear its faux edges");
        }
    std::vector<int> loop;
    int start = next.begin()->first, v = start;
    do {
      loop.push_back(v);
      auto it = next.find(v);
      if (it == next.end() || loop.size() > next.size())
        throw InvalidInput("a polygon (faces joined by faux edges) has no simple border");
      v = it->second;
    } while (v != start);
    if (loop.size() != next.size())
      throw InvalidInput("a polygon (faces joined by faux edges) has holes: clear its faux edges");
    polygons.push_back(std::move(loop));
  }
  if (polygon_of_face) *polygon_of_face = std::move(region);
  return polygons;
}

QuadMesh quads_from_polygons(const std::vector<Point3>& points, const std::vector<std::vector<int>>& polygons,
                             std::vector<int>* polygon_of_quad) {
  QuadMesh out;
  out.points = points;
  if (polygon_of_quad) polygon_of_quad->clear();
  auto key = [](int a, int b) -> std::pair<int, int> { return std::minmax(a, b); };
  // Edges that get a midpoint: every side of a non-quad, then, so that no midpoint hangs, the
  // opposite side of every quad with a cut side, along the quad strip, until the strip ends
  // (at a non-quad, a boundary, or back on itself).
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> quad_sides;  // edge -> (polygon, side)
  for (int i = 0; i < int(polygons.size()); ++i)
    if (polygons[i].size() == 4)
      for (int s = 0; s < 4; ++s) quad_sides[key(polygons[i][s], polygons[i][(s + 1) % 4])].push_back({i, s});
  std::set<std::pair<int, int>> cut;
  std::vector<std::pair<int, int>> work;
  for (const auto& poly : polygons)
    if (poly.size() != 4)
      for (size_t k = 0; k < poly.size(); ++k)
        if (cut.insert(key(poly[k], poly[(k + 1) % poly.size()])).second) work.push_back(key(poly[k], poly[(k + 1) % poly.size()]));
  while (!work.empty()) {
    const auto e = work.back();
    work.pop_back();
    auto it = quad_sides.find(e);
    if (it == quad_sides.end()) continue;
    for (auto [i, s] : it->second) {
      const auto opposite = key(polygons[i][(s + 2) % 4], polygons[i][(s + 3) % 4]);
      if (cut.insert(opposite).second) work.push_back(opposite);
    }
  }
  std::map<std::pair<int, int>, int> midpoint;
  auto mid = [&](int a, int b) {
    auto it = midpoint.find(key(a, b));
    if (it != midpoint.end()) return it->second;
    out.points.push_back((points[a] + points[b]) * 0.5);
    return midpoint[key(a, b)] = int(out.points.size()) - 1;
  };
  auto emit = [&](int i, std::array<int, 4> q) {
    out.quads.push_back(q);
    if (polygon_of_quad) polygon_of_quad->push_back(i);
  };
  for (int i = 0; i < int(polygons.size()); ++i) {
    const auto& poly = polygons[i];
    const int n = int(poly.size());
    if (n == 4) {
      const bool cut_02 = cut.count(key(poly[0], poly[1])) > 0, cut_13 = cut.count(key(poly[1], poly[2])) > 0;
      if (!cut_02 && !cut_13) { emit(i, {poly[0], poly[1], poly[2], poly[3]}); continue; }
      if (cut_02 && !cut_13) {
        const int m0 = mid(poly[0], poly[1]), m2 = mid(poly[2], poly[3]);
        emit(i, {poly[0], m0, m2, poly[3]});
        emit(i, {m0, poly[1], poly[2], m2});
        continue;
      }
      if (cut_13 && !cut_02) {
        const int m1 = mid(poly[1], poly[2]), m3 = mid(poly[3], poly[0]);
        emit(i, {poly[0], poly[1], m1, m3});
        emit(i, {m3, m1, poly[2], poly[3]});
        continue;
      }
      // crossed by two strips: four quads around the centre, as below
    }
    Point3 centre(0, 0, 0);
    for (int v : poly) centre += points[v];
    out.points.push_back(centre / double(n));
    const int c = int(out.points.size()) - 1;
    for (int k = 0; k < n; ++k) {
      int prev = poly[(k + n - 1) % n], here = poly[k], next = poly[(k + 1) % n];
      emit(i, {here, mid(here, next), c, mid(prev, here)});
    }
  }
  return out;
}

void quads_to_tri_mesh(const QuadMesh& quads, TriMesh& out) { quads_to_tri_mesh(quads, {}, out); }

void quads_to_tri_mesh(const QuadMesh& quads, const std::vector<std::array<int, 3>>& triangles, TriMesh& out) {
  out.Clear();
  vcg::tri::Allocator<TriMesh>::AddVertices(out, quads.points.size());
  vcg::tri::Allocator<TriMesh>::AddFaces(out, 2 * quads.quads.size() + triangles.size());
  for (size_t i = 0; i < quads.points.size(); ++i) out.vert[i].P() = quads.points[i];
  for (size_t q = 0; q < quads.quads.size(); ++q) {
    const auto& c = quads.quads[q];
    auto& t0 = out.face[2 * q];
    auto& t1 = out.face[2 * q + 1];
    t0.V(0) = &out.vert[c[0]]; t0.V(1) = &out.vert[c[1]]; t0.V(2) = &out.vert[c[2]];
    t1.V(0) = &out.vert[c[0]]; t1.V(1) = &out.vert[c[2]]; t1.V(2) = &out.vert[c[3]];
    t0.SetF(2);  // c2 -> c0 is the quad's diagonal
    t1.SetF(0);  // c0 -> c2
  }
  for (size_t t = 0; t < triangles.size(); ++t) {
    auto& f = out.face[2 * quads.quads.size() + t];
    for (int z = 0; z < 3; ++z) f.V(z) = &out.vert[triangles[t][z]];
  }
  out.bbox.SetNull();
  for (const auto& v : out.vert) out.bbox.Add(v.cP());
}

}  // namespace mr::quadsub
