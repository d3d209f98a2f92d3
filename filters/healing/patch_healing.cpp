#include "healing/patch_healing.h"

#include "common/errors.h"
#include "common/mesh_validation.h"
#include "healing/border_pairing.h"
#include "healing/open_borders.h"
#include "healing/orientation.h"
#include "healing/region_grouping.h"
#include "healing/seam_welding.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace mr::healing {
namespace {

void check_params(const Params& p, double diag) {
  if (!std::isfinite(p.vertex_tolerance) || p.vertex_tolerance <= 0)
    throw InvalidInput("vertex_tolerance must be a positive length (got " + std::to_string(p.vertex_tolerance) + ")");
  if (!std::isfinite(p.edge_tolerance) || p.edge_tolerance < 0)
    throw InvalidInput("edge_tolerance must be 0 (same as vertex_tolerance) or a positive length");
  if (!(p.feature_angle_deg > 0 && p.feature_angle_deg < 180))
    throw InvalidInput("feature_angle must be in (0, 180) degrees");
  if (diag > 0 && p.vertex_tolerance > 0.25 * diag)
    throw InvalidInput("vertex_tolerance is more than a quarter of the bounding box diagonal: "
                       "it would weld unrelated parts; use a tolerance near the gap width");
}

/// Bounding-box diagonal; throws on empty input, missing faces, NaN or bad indices.
double check_surface(const std::vector<Point3>& points, const std::vector<std::array<int, 3>>& faces) {
  if (points.empty()) throw InvalidInput("the input mesh is empty: load a triangle mesh first");
  if (faces.empty())
    throw InvalidInput("the input mesh has no faces (a point cloud?): this filter needs triangle patches");
  Box3 box;
  for (const auto& p : points) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw InvalidInput("the input mesh has NaN or infinite vertex coordinates: fix or delete those vertices first");
    box.Add(p);
  }
  for (const auto& t : faces)
    for (int v : t)
      if (v < 0 || v >= int(points.size())) throw InvalidInput("a face refers to a vertex that does not exist");
  return box.Diag();
}

}  // namespace

std::vector<int> connected_patches(int vertex_count, const std::vector<std::array<int, 3>>& faces) {
  UnionFind uf(vertex_count);
  for (const auto& t : faces) { uf.unite(t[0], t[1]); uf.unite(t[0], t[2]); }
  std::vector<int> id_of_root(vertex_count, -1), patch(faces.size());
  int next = 0;
  for (size_t f = 0; f < faces.size(); ++f) {
    int& id = id_of_root[uf.find(faces[f][0])];
    if (id < 0) id = next++;
    patch[f] = id;
  }
  return patch;
}

Result heal(const TriMesh& mesh, const std::vector<int>& face_patch, const Params& params) {
  require_triangle_surface(mesh);
  std::vector<Point3> points;
  for (const auto& v : mesh.vert) points.push_back(v.cP());
  std::vector<std::array<int, 3>> faces;
  for (const auto& f : mesh.face)
    faces.push_back({int(vcg::tri::Index(mesh, f.cV(0))), int(vcg::tri::Index(mesh, f.cV(1))),
                     int(vcg::tri::Index(mesh, f.cV(2)))});
  return heal(std::move(points), std::move(faces), face_patch, params);
}

Result heal(std::vector<Point3> points, std::vector<std::array<int, 3>> faces, std::vector<int> face_patch,
            const Params& params) {
  const auto start = std::chrono::steady_clock::now();
  check_params(params, check_surface(points, faces));
  if (!face_patch.empty() && face_patch.size() != faces.size())
    throw InvalidInput("the patch labels do not match the faces (" + std::to_string(face_patch.size()) +
                       " labels for " + std::to_string(faces.size()) + " faces)");
  if (face_patch.empty()) face_patch = connected_patches(int(points.size()), faces);
  const double vtol = params.vertex_tolerance;
  const double etol = params.edge_tolerance > 0 ? params.edge_tolerance : vtol;

  Result r;
  {
    std::vector<int> labels(face_patch);
    std::sort(labels.begin(), labels.end());
    r.patches_in = int(std::unique(labels.begin(), labels.end()) - labels.begin());
  }
  Soup soup{std::move(points), std::move(faces), face_patch};
  const Pairing pairing = pair_borders(soup, vtol, etol);
  r.boundary_edges_before = pairing.border_edges;
  r.borders_paired = pairing.pairs;
  r.pairs_rejected = pairing.rejected;
  r.t_junctions_split = pairing.t_junctions;

  Welded welded = weld_classes(soup, pairing.weld_class);
  r.duplicate_faces_removed = welded.duplicate_faces_removed;
  for (double m : welded.move)
    if (m > 0) { ++r.vertices_moved; r.largest_move = std::max(r.largest_move, m); }
  std::vector<std::array<int, 2>> seams;
  for (const auto& e : pairing.seam_edges) {
    const int a = welded.new_index[e[0]], b = welded.new_index[e[1]];
    if (a >= 0 && b >= 0) seams.push_back({a, b});
  }

  const Orientation orientation = orient_consistently(welded.soup, params.orient_outward);
  r.faces_flipped = orientation.faces_flipped;
  r.orientation_conflicts = orientation.conflicts;

  const EdgeTable edges = soup_edges(welded.soup);
  const OpenBorders open = find_open_borders(welded.soup, edges, 10 * vtol);
  r.boundary_edges_after = open.edges;
  r.open_loops = open.loops;
  r.gaps_left = open.gaps;
  r.largest_gap = open.largest_gap;
  r.open_border = open.side_open;
  for (int e = 0; e < edges.edge_count(); ++e) r.non_manifold_edges_after += edges.valence(e) > 2;

  Regions regions = group_patches(welded.soup, edges, seams, params.feature_angle_deg);
  r.feature = std::move(regions.feature);
  r.face_group = std::move(regions.group);
  r.feature_edges = regions.feature_edges;
  r.groups = regions.groups;

  r.points = std::move(welded.soup.pos);
  r.faces = std::move(welded.soup.tri);
  r.face_patch = welded.soup.patch;
  r.vertex_move = std::move(welded.move);
  r.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace mr::healing
