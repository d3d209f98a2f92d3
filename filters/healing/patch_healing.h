// Healing gaps, overlaps and T-junctions between surface patches, after
// Uva, Monno and Hamann, "A New Method for the Repair of CAD Data with
// Discontinuities" (1999), on tessellated patches:
//   1. border vertices of different patches within `vertex_tolerance` become
//      candidate clusters;
//   2. a border vertex near the interior of another border edge splits that
//      edge (T-junction), so both sides get matching vertices;
//   3. border edges whose ends fall in the same clusters are paired and
//      verified against `edge_tolerance`; unverified pairs stay open;
//   4. paired borders move to their average and are welded;
//   5. orientation is made consistent (outward for closed parts);
//   6. open borders that remain are reported with the widest gap;
//   7. welded seams sharper than `feature_angle` become feature lines and
//      patches are grouped into regions bounded by them.
#pragma once

#include "common/tri_mesh.h"

#include <array>
#include <vector>

namespace mr::healing {

struct Params {
  double vertex_tolerance = 0;  ///< absolute; > 0
  double edge_tolerance = 0;    ///< absolute; 0 means "same as vertex_tolerance"
  double feature_angle_deg = 30;
  bool orient_outward = true;   ///< closed parts get outward normals
};

struct Result {
  std::vector<Point3> points;                   ///< healed surface (compact) ...
  std::vector<std::array<int, 3>> faces;        ///< ... as indexed triangles
  std::vector<int> face_patch;                  ///< input patch of every output face
  std::vector<int> face_group;                  ///< region of every output face
  std::vector<std::array<bool, 3>> feature;     ///< face side is a feature line
  std::vector<std::array<bool, 3>> open_border; ///< face side is still a boundary edge
  std::vector<double> vertex_move;              ///< how far each output vertex moved

  int patches_in = 0;
  int borders_paired = 0;        ///< border edge pairs welded
  int pairs_rejected = 0;        ///< pairs that failed the edge tolerance check
  int t_junctions_split = 0;
  int vertices_moved = 0;
  double largest_move = 0;
  int boundary_edges_before = 0;
  int boundary_edges_after = 0;
  int non_manifold_edges_after = 0;
  int open_loops = 0;            ///< boundary loops left open
  int gaps_left = 0;             ///< open border edges facing another open border within 10x tolerance
  double largest_gap = 0;        ///< widest such gap (0 if none)
  int duplicate_faces_removed = 0;
  int faces_flipped = 0;
  int orientation_conflicts = 0; ///< edges that stay inconsistently oriented (non-orientable parts)
  int feature_edges = 0;
  int groups = 0;
  double time_ms = 0;
};

/// Heals the indexed triangles. `face_patch` gives the patch of every face;
/// empty means "connected components" (faces sharing a vertex index are one patch).
/// \throw InvalidInput on an empty or NaN mesh, bad indices or bad parameters.
Result heal(std::vector<Point3> points, std::vector<std::array<int, 3>> faces, std::vector<int> face_patch,
            const Params& params);

/// The same on a VCG mesh.
Result heal(const TriMesh& mesh, const std::vector<int>& face_patch, const Params& params);

/// Patches as connected components over shared vertex indices, numbered in
/// order of their first face.
std::vector<int> connected_patches(int vertex_count, const std::vector<std::array<int, 3>>& faces);

}  // namespace mr::healing
