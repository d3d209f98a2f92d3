#include "quadsub/interpolatory_subdivision.h"

#include "common/errors.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>

namespace mr::quadsub {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::pair<int, int> key(int a, int b) { return std::minmax(a, b); }

// Quad mesh with crease edges cut open: every vertex is split into one copy per
// sector between creases, so creases become boundaries of sub-meshes.
struct CutMesh {
  QuadMesh mesh;
  std::vector<int> origin;      // original vertex of each copy
  std::vector<char> corner;     // the boundary breaks here (reflection rule)
};

CutMesh cut_along_creases(const QuadMesh& m, const EdgeList& creases, double corner_angle_deg) {
  const int nv = int(m.points.size()), nq = int(m.quads.size());
  std::map<std::pair<int, int>, std::vector<int>> edge_corners;  // edge -> 4*face+side
  for (int q = 0; q < nq; ++q)
    for (int s = 0; s < 4; ++s) edge_corners[key(m.quads[q][s], m.quads[q][(s + 1) % 4])].push_back(4 * q + s);
  std::map<std::pair<int, int>, char> is_crease;
  for (auto [a, b] : creases) is_crease[key(a, b)] = 1;

  // Union-find over face corners: corners around a vertex join across non-crease edges.
  std::vector<int> parent(4 * nq);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) { while (parent[i] != i) i = parent[i] = parent[parent[i]]; return i; };
  std::vector<int> border_edges(nv, 0);  // boundary + crease edges at each original vertex
  for (const auto& [e, list] : edge_corners) {
    if (list.size() > 2)
      throw TopologyError("the quad mesh has a non-manifold edge: repair it first "
                          "(Cleaning and Repairing > Repair non Manifold Edges)");
    const bool cut = list.size() == 1 || is_crease.count(e);
    if (cut) { ++border_edges[e.first]; ++border_edges[e.second]; continue; }
    int c0 = list[0], c1 = list[1];
    int q0 = c0 / 4, s0 = c0 % 4, q1 = c1 / 4, s1 = c1 % 4;
    if (m.quads[q0][s0] == m.quads[q1][s1])
      throw TopologyError("the quad mesh is not consistently oriented: run "
                          "Normals > Re-Orient all faces coherently first");
    // corner (q0,s0) holds m.quads[q0][s0] == m.quads[q1][(s1+1)%4] and vice versa
    auto join = [&](int a, int b) { parent[find(a)] = find(b); };
    join(4 * q0 + s0, 4 * q1 + (s1 + 1) % 4);
    join(4 * q0 + (s0 + 1) % 4, 4 * q1 + s1);
  }
  CutMesh cut;
  cut.mesh.quads = m.quads;
  std::map<int, int> copy_of_root;
  for (int q = 0; q < nq; ++q)
    for (int s = 0; s < 4; ++s) {
      int root = find(4 * q + s);
      auto [it, fresh] = copy_of_root.emplace(root, int(cut.origin.size()));
      if (fresh) {
        cut.origin.push_back(m.quads[q][s]);
        cut.mesh.points.push_back(m.points[m.quads[q][s]]);
      }
      cut.mesh.quads[q][s] = it->second;
    }
  cut.corner.assign(cut.origin.size(), 0);
  for (size_t c = 0; c < cut.origin.size(); ++c) {
    int b = border_edges[cut.origin[c]];
    cut.corner[c] = (b != 0 && b != 2) ? 1 : 0;  // three or more patches meet, or a dangling crease
  }
  (void)corner_angle_deg;  // the turning test needs the rings: done in Topology
  return cut;
}

// Rings around every vertex of a (cut) quad mesh.
struct Topology {
  struct Ring {
    std::vector<int> p;  // neighbours in order; a boundary ring starts and ends on the boundary
    std::vector<int> d;  // d[i]: diagonal of the face between p[i] and p[i+1]
    bool boundary = false;
  };
  std::vector<Ring> ring;
  std::map<std::pair<int, int>, std::array<int, 2>> edge_faces;  // -1 where there is none

  explicit Topology(const QuadMesh& m) {
    const int nv = int(m.points.size());
    std::vector<std::vector<std::pair<int, int>>> corners(nv);  // (face, corner)
    for (int q = 0; q < int(m.quads.size()); ++q)
      for (int s = 0; s < 4; ++s) {
        corners[m.quads[q][s]].push_back({q, s});
        auto& ef = edge_faces.try_emplace(key(m.quads[q][s], m.quads[q][(s + 1) % 4]), std::array<int, 2>{-1, -1})
                       .first->second;
        (ef[0] < 0 ? ef[0] : ef[1]) = q;
      }
    ring.resize(nv);
    for (int v = 0; v < nv; ++v) {
      if (corners[v].empty()) continue;
      std::map<int, std::pair<int, int>> by_first;  // p_i -> corner whose face starts the sector at p_i
      std::map<int, int> last_seen;
      for (auto [q, s] : corners[v]) {
        by_first[m.quads[q][(s + 1) % 4]] = {q, s};
        last_seen[m.quads[q][(s + 3) % 4]] = q;
      }
      // a boundary vertex starts at the neighbour no face closes
      int start = -1;
      for (auto& [p, c] : by_first)
        if (!last_seen.count(p)) { start = p; break; }
      Ring& r = ring[v];
      r.boundary = start >= 0;
      int p = start >= 0 ? start : by_first.begin()->first;
      const int first = p;
      for (size_t steps = 0; steps <= corners[v].size(); ++steps) {
        r.p.push_back(p);
        auto it = by_first.find(p);
        if (it == by_first.end()) break;  // reached the other boundary side
        auto [q, s] = it->second;
        r.d.push_back(m.quads[q][(s + 2) % 4]);
        p = m.quads[q][(s + 3) % 4];
        if (!r.boundary && p == first) break;
      }
      if (r.d.size() != corners[v].size())
        throw TopologyError("the quad mesh has a non-manifold vertex (two fans meet at one vertex): "
                            "repair it first (Cleaning and Repairing > Repair non Manifold Vertices)");
    }
  }
};

class Step {
public:
  Step(const CutMesh& cut, const Params& params)
      : m_(cut.mesh), corner_(cut.corner), cusp_(cut.origin.size(), 0), topo_(cut.mesh), a_((8.0 + params.w) / 16.0),
        b_(-params.w / 16.0), gamma_(diagonal_correction_weight(params.w)) {
    std::vector<char> is_cusp;
    for (int v : params.cusp_vertices) {
      if (v >= int(is_cusp.size())) is_cusp.resize(v + 1, 0);
      is_cusp[v] = 1;
    }
    for (size_t c = 0; c < cut.origin.size(); ++c)
      cusp_[c] = cut.origin[c] < int(is_cusp.size()) && is_cusp[cut.origin[c]];
    const double cos_corner = std::cos(params.corner_angle_deg * kPi / 180.0);
    for (int v = 0; v < int(m_.points.size()); ++v) {
      const auto& r = topo_.ring[v];
      if (!r.boundary || corner_[v]) continue;
      if (r.p.size() < 2) { corner_[v] = 1; continue; }
      Point3 in = m_.points[v] - m_.points[r.p.front()], out = m_.points[r.p.back()] - m_.points[v];
      double len = in.Norm() * out.Norm();
      if (len == 0 || (in * out) / len < cos_corner) corner_[v] = 1;  // a sharp turn
    }
  }

  // The point beyond v on the line from neighbour u through v (actual, virtual or ghost).
  Point3 beyond(int v, int u) const {
    const auto& r = topo_.ring[v];
    const Point3& pv = m_.points[v];
    // A cusp is the limit of a hole shrunk to v: each edge reaching it sees one inner
    // neighbour, whose ghost 2p - mean(inner) is the reflection of u.
    if (cusp_[v]) return pv * 2.0 - m_.points[u];
    if (r.boundary) {
      const bool along_border = u == r.p.front() || u == r.p.back();
      if (along_border && is_border_edge(u, v)) {
        if (corner_[v]) return pv * 2.0 - m_.points[u];  // reflection d* = 2c - b
        return m_.points[u == r.p.front() ? r.p.back() : r.p.front()];
      }
      // an inner edge reaching the border: extrapolate a ghost point
      Point3 mean(0, 0, 0);
      for (size_t i = 1; i + 1 < r.p.size(); ++i) mean += m_.points[r.p[i]];
      mean /= double(r.p.size() - 2);
      return pv * 2.0 - mean;
    }
    const int n = int(r.p.size());
    const int j = int(std::find(r.p.begin(), r.p.end(), u) - r.p.begin());
    auto P = [&](int i) { return m_.points[r.p[((j + i) % n + n) % n]]; };
    auto D = [&](int i) { return m_.points[r.d[((j + i) % n + n) % n]]; };
    if (n == 4) return P(2);
    Point3 sum_p(0, 0, 0), sum_d(0, 0, 0);
    for (int i = 0; i < n; ++i) { sum_p += m_.points[r.p[i]]; sum_d += m_.points[r.d[i]]; }
    const double s = 4.0 / n;
    return sum_p * s - (P(-1) + P(0) + P(1)) + (sum_d * s - (D(-2) + D(-1) + D(0) + D(1))) * gamma_;
  }

  Point3 edge_point(int a, int b) const {
    return (m_.points[a] + m_.points[b]) * a_ + (beyond(a, b) + beyond(b, a)) * b_;
  }

  bool is_border_edge(int a, int b) const {
    auto it = topo_.edge_faces.find(key(a, b));
    return it != topo_.edge_faces.end() && it->second[1] < 0;
  }

  const Topology& topology() const { return topo_; }
  double a() const { return a_; }
  double b() const { return b_; }

private:
  const QuadMesh& m_;
  std::vector<char> corner_;
  std::vector<char> cusp_;
  Topology topo_;
  double a_, b_, gamma_;
};

}  // namespace

double diagonal_correction_weight(double w) { return -w / (8.0 + w); }

QuadMesh subdivide_step(const QuadMesh& mesh, const EdgeList& creases, const Params& params, EdgeList* new_creases,
                        std::vector<std::pair<Point3, Point3>>* face_points_by_direction) {
  const CutMesh cut = cut_along_creases(mesh, creases, params.corner_angle_deg);
  const Step step(cut, params);
  const QuadMesh& m = cut.mesh;
  const int nq = int(m.quads.size());

  // Edge points, computed on the cut mesh, stored per original edge (crease sides agree).
  std::map<std::pair<int, int>, int> edge_index;  // original edge -> new vertex
  std::map<std::pair<int, int>, Point3> cut_edge_point;
  QuadMesh out;
  out.points = mesh.points;  // old vertices never move
  for (int q = 0; q < nq; ++q)
    for (int s = 0; s < 4; ++s) {
      int a = m.quads[q][s], b = m.quads[q][(s + 1) % 4];
      auto ck = key(a, b);
      if (cut_edge_point.count(ck)) continue;
      Point3 e = step.edge_point(a, b);
      cut_edge_point[ck] = e;
      auto ok = key(cut.origin[a], cut.origin[b]);
      if (edge_index.emplace(ok, int(out.points.size())).second) out.points.push_back(e);
    }
  auto E = [&](int q, int s) { return cut_edge_point.at(key(m.quads[q][s], m.quads[q][(s + 1) % 4])); };
  // The edge point one face further across side s of quad q, or a linear ghost.
  auto beyond_edge = [&](int q, int s) {
    int a = m.quads[q][s], b = m.quads[q][(s + 1) % 4];
    const auto& faces = step.topology().edge_faces.at(key(a, b));
    int g = faces[0] == q ? faces[1] : faces[0];
    if (g < 0) return E(q, s) * 2.0 - E(q, (s + 2) % 4);
    int t = 0;
    while (!(m.quads[g][t] == b && m.quads[g][(t + 1) % 4] == a)) ++t;
    return E(g, (t + 2) % 4);
  };
  std::vector<int> face_vertex(nq);
  if (face_points_by_direction) face_points_by_direction->resize(nq);
  for (int q = 0; q < nq; ++q) {
    Point3 dir[2];
    for (int s = 0; s < 2; ++s)
      dir[s] = (E(q, s) + E(q, s + 2)) * step.a() + (beyond_edge(q, s) + beyond_edge(q, s + 2)) * step.b();
    if (face_points_by_direction) (*face_points_by_direction)[q] = {dir[0], dir[1]};
    face_vertex[q] = int(out.points.size());
    out.points.push_back((dir[0] + dir[1]) * 0.5);
  }
  for (int q = 0; q < nq; ++q) {
    const auto& c = mesh.quads[q];
    auto ev = [&](int s) { return edge_index.at(key(c[s % 4], c[(s + 1) % 4])); };
    for (int k = 0; k < 4; ++k) out.quads.push_back({c[k], ev(k), face_vertex[q], ev(k + 3)});
  }
  if (new_creases) {
    new_creases->clear();
    for (auto [a, b] : creases) {
      auto it = edge_index.find(key(a, b));
      if (it == edge_index.end()) continue;
      new_creases->push_back({a, it->second});
      new_creases->push_back({it->second, b});
    }
  }
  return out;
}

Result prepare_level_zero(const std::vector<Point3>& points, const std::vector<std::vector<int>>& polygons,
                          const EdgeList& marked_creases, const Params& params, std::vector<int>* polygon_of_quad) {
  const double max_w = std::sqrt(5.0) - 1.0;
  if (!(params.w >= 0.0 && params.w <= max_w))
    throw InvalidInput("tension w must lie in [0, sqrt(5)-1 = 1.2361], got " + std::to_string(params.w));
  if (params.iterations < 1 || params.iterations > 8)
    throw InvalidInput("iterations must lie in [1, 8], got " + std::to_string(params.iterations));
  if (!(params.crease_angle_deg >= 0.0 && params.crease_angle_deg < 180.0))
    throw InvalidInput("crease_angle must lie in [0, 180) degrees (0 = off), got " + std::to_string(params.crease_angle_deg));
  if (!(params.corner_angle_deg >= 0.0 && params.corner_angle_deg <= 180.0))
    throw InvalidInput("corner_angle must lie in [0, 180] degrees, got " + std::to_string(params.corner_angle_deg));
  if (points.empty()) throw InvalidInput("the input mesh is empty");
  if (polygons.empty()) throw InvalidInput("the input mesh has no faces (a point cloud?): this filter needs a quad mesh");
  for (const auto& p : points)
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw InvalidInput("the input mesh has NaN or infinite vertex coordinates");
  for (int v : params.cusp_vertices)
    if (v < 0 || v >= int(points.size()))
      throw InvalidInput("cusp vertex " + std::to_string(v) + " is not a vertex of the input (0.." +
                         std::to_string(points.size() - 1) + ")");

  Result result;
  result.vertices_in = int(points.size());
  result.faces_in = int(polygons.size());
  QuadMesh mesh = quads_from_polygons(points, polygons, polygon_of_quad);
  EdgeList creases = marked_creases;
  if (params.crease_angle_deg > 0) {
    // Quad normals by the cross product of the diagonals; an edge between quads whose normals
    // differ by more than the crease angle is a crease.
    const double cos_crease = std::cos(params.crease_angle_deg * kPi / 180.0);
    std::map<std::pair<int, int>, std::vector<int>> faces_of;
    std::vector<Point3> normal(mesh.quads.size());
    for (size_t q = 0; q < mesh.quads.size(); ++q) {
      const auto& c = mesh.quads[q];
      Point3 n = (mesh.points[c[2]] - mesh.points[c[0]]) ^ (mesh.points[c[3]] - mesh.points[c[1]]);
      double len = n.Norm();
      normal[q] = len > 0 ? n / len : Point3(0, 0, 0);
      for (int s = 0; s < 4; ++s) faces_of[key(c[s], c[(s + 1) % 4])].push_back(int(q));
    }
    for (const auto& [e, fs] : faces_of)
      if (fs.size() == 2 && normal[fs[0]] * normal[fs[1]] < cos_crease) creases.push_back(e);
  }
  result.crease_edges_in = int(creases.size());
  {
    std::vector<int> cusps = params.cusp_vertices;
    std::sort(cusps.begin(), cusps.end());
    result.cusps = int(std::unique(cusps.begin(), cusps.end()) - cusps.begin());
  }
  {
    const Topology topo(cut_along_creases(mesh, {}, params.corner_angle_deg).mesh);
    for (const auto& r : topo.ring) result.extraordinary_vertices += !r.boundary && !r.p.empty() && r.p.size() != 4;
  }
  result.mesh = std::move(mesh);
  result.creases = std::move(creases);
  return result;
}

Result subdivide(const std::vector<Point3>& points, const std::vector<std::vector<int>>& polygons,
                 const EdgeList& marked_creases, const Params& params) {
  Result result = prepare_level_zero(points, polygons, marked_creases, params);
  for (int level = 0; level < params.iterations; ++level) {
    EdgeList next;
    result.mesh = subdivide_step(result.mesh, result.creases, params, &next);
    result.creases.swap(next);
  }
  result.levels = params.iterations;
  return result;
}

}  // namespace mr::quadsub
