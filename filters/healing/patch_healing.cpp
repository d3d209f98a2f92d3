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

void check_params(const Params& p, const TriMesh& mesh) {
  if (!std::isfinite(p.vertex_tolerance) || p.vertex_tolerance <= 0)
    throw InvalidInput("vertex_tolerance must be a positive length (got " + std::to_string(p.vertex_tolerance) + ")");
  if (!std::isfinite(p.edge_tolerance) || p.edge_tolerance < 0)
    throw InvalidInput("edge_tolerance must be 0 (same as vertex_tolerance) or a positive length");
  if (!(p.feature_angle_deg > 0 && p.feature_angle_deg < 180))
    throw InvalidInput("feature_angle must be in (0, 180) degrees");
  const double diag = mesh.bbox.Diag();
  if (diag > 0 && p.vertex_tolerance > 0.25 * diag)
    throw InvalidInput("vertex_tolerance is more than a quarter of the bounding box diagonal: "
                       "it would weld unrelated parts; use a tolerance near the gap width");
}

Soup to_soup(const TriMesh& mesh, const std::vector<int>& face_patch) {
  Soup s;
  s.pos.reserve(mesh.vert.size());
  for (const auto& v : mesh.vert) s.pos.push_back(v.cP());
  for (size_t f = 0; f < mesh.face.size(); ++f) {
    const auto& face = mesh.face[f];
    s.tri.push_back({int(vcg::tri::Index(mesh, face.cV(0))), int(vcg::tri::Index(mesh, face.cV(1))),
                     int(vcg::tri::Index(mesh, face.cV(2)))});
    s.patch.push_back(face_patch[f]);
  }
  return s;
}

}  // namespace

std::vector<int> connected_patches(const TriMesh& mesh) {
  UnionFind uf(int(mesh.vert.size()));
  for (const auto& f : mesh.face) {
    uf.unite(int(vcg::tri::Index(mesh, f.cV(0))), int(vcg::tri::Index(mesh, f.cV(1))));
    uf.unite(int(vcg::tri::Index(mesh, f.cV(0))), int(vcg::tri::Index(mesh, f.cV(2))));
  }
  std::vector<int> id_of_root(mesh.vert.size(), -1), patch(mesh.face.size());
  int next = 0;
  for (size_t f = 0; f < mesh.face.size(); ++f) {
    int& id = id_of_root[uf.find(int(vcg::tri::Index(mesh, mesh.face[f].cV(0))))];
    if (id < 0) id = next++;
    patch[f] = id;
  }
  return patch;
}

Result heal(const TriMesh& mesh, const std::vector<int>& face_patch_in, const Params& params) {
  const auto start = std::chrono::steady_clock::now();
  require_triangle_surface(mesh);
  check_params(params, mesh);
  if (!face_patch_in.empty() && face_patch_in.size() != mesh.face.size())
    throw InvalidInput("the patch labels do not match the faces (" + std::to_string(face_patch_in.size()) +
                       " labels for " + std::to_string(mesh.face.size()) + " faces)");
  const std::vector<int> face_patch = face_patch_in.empty() ? connected_patches(mesh) : face_patch_in;
  const double vtol = params.vertex_tolerance;
  const double etol = params.edge_tolerance > 0 ? params.edge_tolerance : vtol;

  Result r;
  {
    std::vector<int> labels(face_patch);
    std::sort(labels.begin(), labels.end());
    r.patches_in = int(std::unique(labels.begin(), labels.end()) - labels.begin());
  }
  Soup soup = to_soup(mesh, face_patch);
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

  const OpenBorders open = find_open_borders(welded.soup, 10 * vtol);
  r.boundary_edges_after = open.edges;
  r.open_loops = open.loops;
  r.gaps_left = open.gaps;
  r.largest_gap = open.largest_gap;
  r.open_border = open.side_open;
  for (const auto& e : soup_edges(welded.soup)) r.non_manifold_edges_after += e.sides.size() > 2;

  Regions regions = group_patches(welded.soup, seams, params.feature_angle_deg);
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
