// Feature lines and surface patches of a triangulated surface, after
// R. Löhner, "Regridding Surface Triangulations", J. Comput. Phys. 126 (1996), section 2.
#pragma once

#include "common/tri_mesh.h"

#include <array>
#include <vector>

namespace mr::features {

struct Params {
  /// An edge is a ridge when its face normals differ by more than this (degrees, (0,180)).
  double ridge_angle_deg = 30.0;
  /// Two ridges meeting at a vertex make it a corner when they turn by more than this (degrees, [0,180]).
  double corner_angle_deg = 45.0;
  /// Also treat face edges flagged with FaceEdgeS (MeshLab's edge selection) as ridges.
  bool use_selected_edges_as_ridges = false;
  /// Patches with fewer faces merge into their largest neighbour (0 = off).
  int min_patch_faces = 0;
  /// Feature-noise suppression (absolute length, 0 = keep every ridge): repeatedly drops lines
  /// shorter than this with a dangling end (an end vertex on that one ridge only) and closed
  /// ridge loops shorter than this, ridges an element of this size cannot represent; then the
  /// borders of sliver patches and of crumples (patches turned over, by more than 90 degrees,
  /// against every neighbour, narrower than this on average). Boundary and non-manifold edges
  /// are never dropped, selected edges only around crumples.
  double min_line_length = 0;
  /// The suppression keeps the sliver patches bordered by a ridge sharper than 60 degrees
  /// (faces' normals further apart): merged across such a fold, a patch is one the advancing
  /// front cannot mesh (box.STL united). Off by default: a scan's noise has such slivers too,
  /// and dropping them gives better elements there.
  bool keep_folded_slivers = false;
  /// The suppression drops crumples (see min_line_length); false keeps them as patches.
  bool drop_crumples = true;
};

/// One chain of ridge edges between two corners, or a closed loop without corners.
struct DiscreteLine {
  std::vector<int> vertices;  ///< vertex indices in order; a closed line repeats no vertex
  bool closed = false;
};

struct Result {
  std::vector<std::array<bool, 3>> ridge;  ///< per face and side: is that edge a ridge
  std::vector<int> patch_of_face;          ///< 0..patch_count-1
  std::vector<int> corners;                ///< vertex indices, increasing
  std::vector<DiscreteLine> lines;
  int ridge_edges = 0;        ///< undirected ridge edges (boundary and non-manifold included)
  int boundary_edges = 0;
  int non_manifold_edges = 0;
  int patch_count = 0;
  int merged_patches = 0;     ///< patches removed by the minimum-size merge
  int suppressed_lines = 0;   ///< short dangling lines, loops and sliver patches dropped by min_line_length
  int suppressed_ridge_edges = 0;  ///< their ridge edges
  int suppressed_folded_slivers = 0;  ///< of the sliver patches, those bordered by a fold (Params::keep_folded_slivers)
  int suppressed_crumples = 0;  ///< of those, crumples (Params::drop_crumples)
};

/// Detects ridges, corners, discrete lines and patches.
/// \pre mesh is compact.
/// \throw InvalidInput on an empty mesh, a point cloud, NaN coordinates or bad parameters.
Result detect(const TriMesh& mesh, const Params& params);

}  // namespace mr::features
