#include "features/feature_lines.h"

#include "common/edge_table.h"
#include "common/errors.h"
#include "common/mesh_validation.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <string>

namespace mr::features {
namespace {

constexpr double kPi = 3.14159265358979323846;

void check_params(const Params& p) {
  if (!(p.ridge_angle_deg > 0.0 && p.ridge_angle_deg < 180.0))
    throw InvalidInput("ridge_angle must lie in (0, 180) degrees, got " + std::to_string(p.ridge_angle_deg));
  if (!(p.corner_angle_deg >= 0.0 && p.corner_angle_deg <= 180.0))
    throw InvalidInput("corner_angle must lie in [0, 180] degrees, got " + std::to_string(p.corner_angle_deg));
  if (p.min_patch_faces < 0)
    throw InvalidInput("min_patch_faces must be >= 0, got " + std::to_string(p.min_patch_faces));
  if (!(p.min_line_length >= 0) || !std::isfinite(p.min_line_length))
    throw InvalidInput("min_line_length must be >= 0 (0 keeps every ridge), got " + std::to_string(p.min_line_length));
}

// Unit face normals; zero for a degenerate face, which then never makes a ridge by angle.
std::vector<Point3> unit_face_normals(const TriMesh& mesh) {
  std::vector<Point3> normals(mesh.face.size());
  for (size_t f = 0; f < mesh.face.size(); ++f) {
    const auto& face = mesh.face[f];
    Point3 n = (face.cP(1) - face.cP(0)) ^ (face.cP(2) - face.cP(0));
    double len = n.Norm();
    normals[f] = len > 0 ? n / len : Point3(0, 0, 0);
  }
  return normals;
}

// Is edge e a ridge by its shape (boundary, non-manifold, or dihedral angle)?
bool is_shape_ridge(const TriMesh& mesh, const EdgeTable& edges, const std::vector<Point3>& normals,
                    int e, double cos_ridge) {
  if (edges.valence(e) != 2) return true;
  FaceSide a = edges.side(e, 0), b = edges.side(e, 1);
  const Point3& na = normals[a.face];
  Point3 nb = normals[b.face];
  if (na.SquaredNorm() == 0 || nb.SquaredNorm() == 0) return false;
  // Two faces that run the shared edge the same way are inconsistently oriented:
  // compare against the flipped normal so the angle is the real crease angle.
  auto idx = [&](FaceSide s, int k) { return vcg::tri::Index(mesh, mesh.face[s.face].cV((s.side + k) % 3)); };
  if (idx(a, 0) == idx(b, 0)) nb = -nb;
  return na * nb < cos_ridge;
}

// Sharper than this (the cosine between the faces' normals) is a fold for keep_folded_slivers:
// the advancing front's normal test (n . n > 0.5) refuses the surface across it.
constexpr double kCosFold = 0.5;
// Sharper than this (90 degrees) is a face turned over: a narrow patch whose every border turns
// over so is a crumple (faces of a union's sliver step folded back onto a flat side), not a
// feature. (At 120 degrees a crumple of two faces, one turned 100 degrees against the other,
// stayed half: joint.off united with turned copies regridded with points not manifold.)
constexpr double kCosTurnedOver = 0.0;

struct Flood {
  std::vector<int> patch_of_face;
  int count = 0;
};

Flood flood_patches(const TriMesh& mesh, const EdgeTable& edges, const std::vector<char>& edge_is_ridge) {
  const int nf = int(mesh.face.size());
  Flood flood;
  flood.patch_of_face.assign(nf, -1);
  std::vector<int> stack;
  for (int seed = 0; seed < nf; ++seed) {
    if (flood.patch_of_face[seed] >= 0) continue;
    int id = flood.count++;
    flood.patch_of_face[seed] = id;
    stack.push_back(seed);
    while (!stack.empty()) {
      int f = stack.back();
      stack.pop_back();
      for (int z = 0; z < 3; ++z) {
        int e = edges.edge_of(f, z);
        if (edge_is_ridge[e]) continue;
        int g = edges.opposite_face(f, z);
        if (g >= 0 && flood.patch_of_face[g] < 0) {
          flood.patch_of_face[g] = id;
          stack.push_back(g);
        }
      }
    }
  }
  return flood;
}

// Merge patches smaller than min_faces into the neighbouring patch with most faces,
// smallest first; the ridges between merged patches stop being ridges.
int merge_small_patches(const EdgeTable& edges, std::vector<char>& edge_is_ridge, Flood& flood,
                        int min_faces) {
  if (min_faces <= 0 || flood.count <= 1) return 0;
  const int np = flood.count;
  std::vector<int> parent(np);
  for (int i = 0; i < np; ++i) parent[i] = i;
  auto find = [&](int i) { while (parent[i] != i) i = parent[i] = parent[parent[i]]; return i; };
  std::vector<long> size(np, 0);
  for (int p : flood.patch_of_face) ++size[p];
  std::vector<std::vector<int>> neighbours(np);
  for (int e = 0; e < edges.edge_count(); ++e) {
    if (edges.valence(e) != 2) continue;
    int pa = flood.patch_of_face[edges.side(e, 0).face], pb = flood.patch_of_face[edges.side(e, 1).face];
    if (pa != pb) { neighbours[pa].push_back(pb); neighbours[pb].push_back(pa); }
  }
  using Entry = std::pair<long, int>;  // (size, patch): smallest first, ties by id
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int i = 0; i < np; ++i) if (size[i] < min_faces) queue.push({size[i], i});
  int merged = 0;
  while (!queue.empty()) {
    auto [sz, small] = queue.top();
    queue.pop();
    if (find(small) != small || sz != size[small] || size[small] >= min_faces) continue;
    int best = -1;
    for (int n : neighbours[small]) {
      int other = find(n);
      if (other == small) continue;
      if (best < 0 || size[other] > size[best] || (size[other] == size[best] && other < best)) best = other;
    }
    if (best < 0) continue;  // an isolated component: nothing to merge with
    parent[small] = best;
    size[best] += size[small];
    auto& into = neighbours[best];
    into.insert(into.end(), neighbours[small].begin(), neighbours[small].end());
    neighbours[small].clear();
    std::sort(into.begin(), into.end());
    into.erase(std::unique(into.begin(), into.end()), into.end());
    ++merged;
    if (size[best] < min_faces) queue.push({size[best], best});
  }
  if (merged == 0) return 0;
  for (int& p : flood.patch_of_face) p = find(p);
  for (int e = 0; e < edges.edge_count(); ++e)
    if (edge_is_ridge[e] && edges.valence(e) == 2 &&
        flood.patch_of_face[edges.side(e, 0).face] == flood.patch_of_face[edges.side(e, 1).face])
      edge_is_ridge[e] = 0;
  std::vector<int> renumber(np, -1);  // in order of first face
  int next = 0;
  for (int& p : flood.patch_of_face) {
    if (renumber[p] < 0) renumber[p] = next++;
    p = renumber[p];
  }
  flood.count = next;
  return merged;
}

// Ridge edges incident to each vertex, in CSR form.
struct VertexRidges {
  std::vector<int> begin, edge;
  int count(int v) const { return begin[v + 1] - begin[v]; }
};

VertexRidges vertex_ridges(int nv, const EdgeTable& edges, const std::vector<char>& edge_is_ridge) {
  VertexRidges vr;
  vr.begin.assign(nv + 1, 0);
  for (int e = 0; e < edges.edge_count(); ++e)
    if (edge_is_ridge[e]) { ++vr.begin[edges.v0(e) + 1]; ++vr.begin[edges.v1(e) + 1]; }
  for (int v = 0; v < nv; ++v) vr.begin[v + 1] += vr.begin[v];
  vr.edge.resize(vr.begin[nv]);
  std::vector<int> fill(vr.begin.begin(), vr.begin.end() - 1);
  for (int e = 0; e < edges.edge_count(); ++e)
    if (edge_is_ridge[e]) { vr.edge[fill[edges.v0(e)]++] = e; vr.edge[fill[edges.v1(e)]++] = e; }
  return vr;
}

int other_end(const EdgeTable& edges, int e, int v) { return edges.v0(e) == v ? edges.v1(e) : edges.v0(e); }

std::vector<int> find_corners(const TriMesh& mesh, const EdgeTable& edges, const VertexRidges& vr,
                              double corner_angle_deg) {
  const double cos_corner = std::cos(corner_angle_deg * kPi / 180.0);
  std::vector<int> corners;
  for (int v = 0; v < int(mesh.vert.size()); ++v) {
    int n = vr.count(v);
    if (n == 0) continue;
    if (n != 2) { corners.push_back(v); continue; }
    int a = other_end(edges, vr.edge[vr.begin[v]], v);
    int b = other_end(edges, vr.edge[vr.begin[v] + 1], v);
    Point3 in = mesh.vert[v].cP() - mesh.vert[a].cP();
    Point3 out = mesh.vert[b].cP() - mesh.vert[v].cP();
    double li = in.Norm(), lo = out.Norm();
    if (li == 0 || lo == 0) continue;
    if ((in * out) / (li * lo) < cos_corner) corners.push_back(v);  // turns by more than the corner angle
  }
  return corners;
}

std::vector<DiscreteLine> trace_lines(int nv, const EdgeTable& edges, const std::vector<char>& edge_is_ridge,
                                      const VertexRidges& vr, const std::vector<int>& corners) {
  std::vector<char> is_corner(nv, 0), used(edges.edge_count(), 0);
  for (int c : corners) is_corner[c] = 1;
  std::vector<DiscreteLine> lines;
  auto walk = [&](int start, int e) {
    DiscreteLine line;
    line.vertices.push_back(start);
    int v = start;
    while (true) {
      used[e] = 1;
      v = other_end(edges, e, v);
      if (v == start) { line.closed = true; break; }
      line.vertices.push_back(v);
      if (is_corner[v]) break;
      int next = -1;
      for (int k = vr.begin[v]; k < vr.begin[v + 1]; ++k)
        if (!used[vr.edge[k]]) { next = vr.edge[k]; break; }
      if (next < 0) break;
      e = next;
    }
    lines.push_back(std::move(line));
  };
  for (int c : corners)
    for (int k = vr.begin[c]; k < vr.begin[c + 1]; ++k)
      if (!used[vr.edge[k]]) walk(c, vr.edge[k]);
  // What is left are closed loops through non-corner vertices.
  for (int e = 0; e < edges.edge_count(); ++e)
    if (edge_is_ridge[e] && !used[e]) walk(edges.v0(e), e);
  return lines;
}

// The edge between consecutive vertices of a line (both on ridge edges of vr).
int ridge_between(const EdgeTable& edges, const VertexRidges& vr, int a, int b) {
  for (int k = vr.begin[a]; k < vr.begin[a + 1]; ++k)
    if (other_end(edges, vr.edge[k], a) == b) return vr.edge[k];
  return -1;
}

std::vector<int> line_edges(const EdgeTable& edges, const VertexRidges& vr, const DiscreteLine& line) {
  std::vector<int> out;
  const size_t n = line.vertices.size();
  for (size_t k = 0; k + 1 < n + (line.closed ? 1 : 0); ++k)
    out.push_back(ridge_between(edges, vr, line.vertices[k], line.vertices[(k + 1) % n]));
  return out;
}

double edge_length(const TriMesh& mesh, const EdgeTable& edges, int e) {
  return (mesh.vert[edges.v0(e)].cP() - mesh.vert[edges.v1(e)].cP()).Norm();
}

struct Suppressed {
  int lines = 0, edges = 0;
  int folded_slivers = 0;  // sliver patches bordered by a fold among the lines
  int crumples = 0;        // of those, crumples (turned over against the surface around them)
};

// Components of the ridge graph that are simple cycles (every vertex on two ridges, corners
// included) shorter than min_length: a small closed crease, e.g. around a bump of a scan.
int drop_short_cycles(const TriMesh& mesh, const EdgeTable& edges, const VertexRidges& vr,
                      std::vector<char>& edge_is_ridge, const std::vector<char>& keep, double min_length,
                      Suppressed& s) {
  std::vector<char> seen(edges.edge_count(), 0);
  int dropped = 0;
  for (int e0 = 0; e0 < edges.edge_count(); ++e0) {
    if (!edge_is_ridge[e0] || seen[e0]) continue;
    std::vector<int> component{e0}, stack{e0};
    seen[e0] = 1;
    bool cycle = true;
    while (!stack.empty()) {
      const int e = stack.back();
      stack.pop_back();
      for (int v : {edges.v0(e), edges.v1(e)}) {
        if (vr.count(v) != 2) cycle = false;
        for (int k = vr.begin[v]; k < vr.begin[v + 1]; ++k)
          if (!seen[vr.edge[k]]) { seen[vr.edge[k]] = 1; component.push_back(vr.edge[k]); stack.push_back(vr.edge[k]); }
      }
    }
    if (!cycle) continue;
    double length = 0;
    bool kept = false;
    for (int e : component) { length += edge_length(mesh, edges, e); kept = kept || keep[e]; }
    if (kept || length >= min_length) continue;
    for (int e : component) edge_is_ridge[e] = 0;
    s.lines++;
    s.edges += int(component.size());
    dropped++;
  }
  return dropped;
}

// Sliver patches bounded by droppable ridges only: area under a tenth of a min_length square and
// under 0.02 x the squared border length (a triangle with a smallest angle under ~10 degrees, a
// strip ten times longer than wide), e.g. one sliver input face whose three edges are ridges, as a
// scan's crease network makes. An element of this size cannot represent them, and keeping them
// forces their slivers into the output as they stand. Their border ridges go, so they join their
// neighbours. Small patches of good shape (a small cube's sides) stay, and with `keep_folded`
// those bordered by a fold (`fold`, per edge).
constexpr double kSliverArea = 0.1, kSliverShape = 0.02;

int drop_sliver_patches(const TriMesh& mesh, const EdgeTable& edges, std::vector<char>& edge_is_ridge,
                       const std::vector<char>& keep, const std::vector<char>& fold,
                       const std::vector<char>& turned_over, const Params& params, Suppressed& s) {
  const bool keep_folded = params.keep_folded_slivers;
  const double min_length = params.min_line_length;
  const Flood flood = flood_patches(mesh, edges, edge_is_ridge);
  std::vector<double> border(flood.count, 0.0), area(flood.count, 0.0);
  for (size_t f = 0; f < mesh.face.size(); ++f) area[flood.patch_of_face[f]] += 0.5 * vcg::DoubleArea(mesh.face[f]);
  std::vector<char> fixed(flood.count, 0);  // touches an edge that never goes
  std::vector<char> folded(flood.count, 0);  // touches a fold
  std::vector<char> crumpled(flood.count, 1);  // every border turns over
  for (int e = 0; e < edges.edge_count(); ++e) {
    if (!edge_is_ridge[e]) continue;
    const double length = edge_length(mesh, edges, e);
    for (int k = 0; k < edges.valence(e); ++k) {
      const int patch = flood.patch_of_face[edges.side(e, k).face];
      border[patch] += length;
      if (keep[e]) fixed[patch] = 1;
      if (fold[e]) folded[patch] = 1;
      if (!turned_over[e]) crumpled[patch] = 0;
    }
  }
  // A crumple lies in a surface that is smooth around it: the faces across its borders are no
  // fold apart from each other (kCosFold). Else dropping it would join patches a crease
  // separates (box.STL's plates as layers: a patch through a plate corner, its points then not
  // manifold).
  std::vector<std::vector<Point3>> around(flood.count);
  for (int e = 0; e < edges.edge_count(); ++e) {
    if (!edge_is_ridge[e] || edges.valence(e) != 2) continue;
    for (int k = 0; k < 2; ++k) {
      const int patch = flood.patch_of_face[edges.side(e, k).face];
      if (crumpled[patch]) around[patch].push_back(vcg::NormalizedTriangleNormal(mesh.face[edges.side(e, 1 - k).face]));
    }
  }
  for (int p = 0; p < flood.count; ++p)
    for (size_t i = 0; i < around[p].size() && crumpled[p]; ++i)
      for (size_t j = 0; j < i; ++j)
        if (around[p][i] * around[p][j] < kCosFold) {
          crumpled[p] = 0;
          break;
        }
  // Crumples go although a kept edge borders them (an intersection line passing along one): as
  // their own patches they were meshed on top of the side around them (its points then not
  // manifold), and merged with the side but bounded by that edge the front along it faced the
  // wrong way. The kept edge loses that segment; boundary and non-manifold edges never go.
  std::vector<char> island(flood.count, 0), crumple(flood.count, 0);
  for (int p = 0; p < flood.count; ++p) {
    if (!(border[p] > 0) || (keep_folded && folded[p])) continue;
    crumple[p] = params.drop_crumples && crumpled[p] && 2 * area[p] < min_length * border[p];
    island[p] = crumple[p] || (!fixed[p] && area[p] < kSliverArea * min_length * min_length &&
                               area[p] < kSliverShape * border[p] * border[p]);
  }
  int dropped = 0;
  std::vector<char> counted(flood.count, 0);
  for (int e = 0; e < edges.edge_count(); ++e) {
    if (!edge_is_ridge[e] || edges.valence(e) != 2) continue;
    bool on_island = false;
    for (int k = 0; k < edges.valence(e); ++k) {
      const int patch = flood.patch_of_face[edges.side(e, k).face];
      if (!island[patch] || (keep[e] && !crumple[patch])) continue;
      on_island = true;
      if (!counted[patch]) {
        counted[patch] = 1;
        s.lines++;
        s.folded_slivers += folded[patch];
        s.crumples += crumple[patch];
        dropped++;
      }
    }
    if (!on_island) continue;
    edge_is_ridge[e] = 0;
    s.edges++;
  }
  return dropped;
}

// Feature-noise suppression: lines shorter than min_length with a dangling end, and short closed
// lines (a loop from a junction back to it), are dropped; then short simple cycles; then the
// borders of small sliver patches and of crumples. Repeated,
// since a dropped branch can leave a junction with one ridge less. `keep` edges never go but
// around crumples, and boundary and non-manifold edges never.
Suppressed suppress_short_lines(const TriMesh& mesh, const EdgeTable& edges, std::vector<char>& edge_is_ridge,
                                const std::vector<char>& keep, const std::vector<char>& fold,
                                const std::vector<char>& turned_over, const Params& p) {
  Suppressed s;
  if (p.min_line_length <= 0) return s;
  const int nv = int(mesh.vert.size());
  while (true) {
    int dropped = 0;
    const VertexRidges vr = vertex_ridges(nv, edges, edge_is_ridge);
    const auto corners = find_corners(mesh, edges, vr, p.corner_angle_deg);
    const auto lines = trace_lines(nv, edges, edge_is_ridge, vr, corners);
    std::vector<std::vector<int>> to_drop;
    for (const auto& line : lines) {
      const bool dangling = !line.closed && (vr.count(line.vertices.front()) == 1 || vr.count(line.vertices.back()) == 1);
      if (!line.closed && !dangling) continue;
      const std::vector<int> es = line_edges(edges, vr, line);
      double length = 0;
      bool kept = false;
      for (int e : es) { length += edge_length(mesh, edges, e); kept = kept || keep[e]; }
      if (!kept && length < p.min_line_length) to_drop.push_back(es);
    }
    for (const auto& es : to_drop) {
      for (int e : es) edge_is_ridge[e] = 0;
      s.lines++;
      s.edges += int(es.size());
      dropped++;
    }
    const VertexRidges after = vertex_ridges(nv, edges, edge_is_ridge);
    dropped += drop_short_cycles(mesh, edges, after, edge_is_ridge, keep, p.min_line_length, s);
    if (dropped == 0) dropped = drop_sliver_patches(mesh, edges, edge_is_ridge, keep, fold, turned_over, p, s);
    if (dropped == 0) return s;
  }
}

}  // namespace

Result detect(const TriMesh& mesh, const Params& params) {
  check_params(params);
  require_triangle_surface(mesh);
  const int nf = int(mesh.face.size());
  const EdgeTable edges(mesh);
  const auto normals = unit_face_normals(mesh);
  const double cos_ridge = std::cos(params.ridge_angle_deg * kPi / 180.0);

  Result result;
  std::vector<char> edge_is_ridge(edges.edge_count(), 0);
  std::vector<char> keep(edges.edge_count(), 0);  // ridges the noise suppression never drops
  std::vector<char> fold(edges.edge_count(), 0);  // ridges sharper than kCosFold (read only for ridges)
  std::vector<char> turned_over(edges.edge_count(), 0);  // ridges sharper than kCosTurnedOver
  for (int e = 0; e < edges.edge_count(); ++e) {
    int val = edges.valence(e);
    if (val == 1) ++result.boundary_edges;
    if (val > 2) ++result.non_manifold_edges;
    edge_is_ridge[e] = is_shape_ridge(mesh, edges, normals, e, cos_ridge);
    keep[e] = val != 2;
    fold[e] = edge_is_ridge[e] && is_shape_ridge(mesh, edges, normals, e, kCosFold);
    turned_over[e] = fold[e] && is_shape_ridge(mesh, edges, normals, e, kCosTurnedOver);
  }
  if (params.use_selected_edges_as_ridges)
    for (int f = 0; f < nf; ++f)
      for (int z = 0; z < 3; ++z)
        if (mesh.face[f].IsFaceEdgeS(z)) edge_is_ridge[edges.edge_of(f, z)] = keep[edges.edge_of(f, z)] = 1;

  const Suppressed suppressed = suppress_short_lines(mesh, edges, edge_is_ridge, keep, fold, turned_over, params);
  result.suppressed_lines = suppressed.lines;
  result.suppressed_ridge_edges = suppressed.edges;
  result.suppressed_folded_slivers = suppressed.folded_slivers;
  result.suppressed_crumples = suppressed.crumples;

  Flood flood = flood_patches(mesh, edges, edge_is_ridge);
  result.merged_patches = merge_small_patches(edges, edge_is_ridge, flood, params.min_patch_faces);

  const VertexRidges vr = vertex_ridges(int(mesh.vert.size()), edges, edge_is_ridge);
  result.corners = find_corners(mesh, edges, vr, params.corner_angle_deg);
  result.lines = trace_lines(int(mesh.vert.size()), edges, edge_is_ridge, vr, result.corners);

  result.ridge.assign(nf, {false, false, false});
  for (int f = 0; f < nf; ++f)
    for (int z = 0; z < 3; ++z) result.ridge[f][z] = edge_is_ridge[edges.edge_of(f, z)] != 0;
  result.ridge_edges = int(std::count(edge_is_ridge.begin(), edge_is_ridge.end(), 1));
  result.patch_of_face = std::move(flood.patch_of_face);
  result.patch_count = flood.count;
  return result;
}

}  // namespace mr::features
