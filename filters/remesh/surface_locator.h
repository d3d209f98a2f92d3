// Host-face search on a triangulated surface (Löhner 1996, section 3.3): for a
// point near the surface find the face it belongs to and its projection.
// Order of search: neighbour walk from a start face, then a uniform grid of the
// faces, then brute force over the allowed faces.
#pragma once

#include "common/tri_mesh.h"

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace mr::remesh {

/// A triangulated surface as flat arrays, with face normals, face-face adjacency and a group
/// (patch) per face. The locator and the recovery work on it.
struct Surface {
  std::vector<Point3> points;
  std::vector<std::array<int, 3>> faces;
  std::vector<Point3> face_normal;              ///< unit, zero if degenerate
  std::vector<std::array<int, 3>> neighbour;    ///< face across side z (corner z to z+1), -1 if none
  std::vector<int> group;                       ///< patch of each face (0 if unused)

  /// Builds from a mesh; `group` may be empty (all 0). Non-manifold sides get no neighbour.
  static Surface from_mesh(const TriMesh& mesh, const std::vector<int>& group);
  /// Builds from arrays (neighbours computed).
  static Surface from_arrays(std::vector<Point3> points, std::vector<std::array<int, 3>> faces,
                             std::vector<int> group);
  void compute_normals_and_neighbours();
};

/// Where a point lands on the surface.
struct Projection {
  int face = -1;                   ///< host face, -1 if none was found
  Point3 point;                    ///< closest point on the host face
  std::array<double, 3> bary{};    ///< barycentric coordinates of `point` in the host face
  double distance = 0;
};

/// Which search step found the host face (for tests and statistics).
enum class SearchStep { Walk, Grid, BruteForce, None };

class SurfaceLocator {
public:
  /// `cell` is the grid cell edge; it is enlarged if the grid would get too big.
  SurfaceLocator(const Surface& surface, double cell);

  /// Host face of p among faces of `group` (-1 = any group). `normal` (may be zero) filters faces
  /// whose normal disagrees (n_face . normal <= 0.5); `start` (-1 = none) starts the walk.
  /// `radius` bounds the walk and grid search; brute force runs only if both find nothing.
  Projection locate(const Point3& p, int group, const Point3& normal, int start, double radius,
                    SearchStep* step = nullptr) const;
  /// Like locate, without the brute force: face -1 when no allowed face lies within `radius`
  /// (a cheap "is p on the surface" test).
  Projection locate_within(const Point3& p, int group, const Point3& normal, int start, double radius,
                           SearchStep* step = nullptr) const;

  /// Like locate_within with radius `reach`, searched from `first_radius` on in radii 4x larger
  /// while nothing is found. Each step is exact when it finds a face within its radius, and small
  /// radii keep walks and grid boxes short: for points known to lie near the surface this is much
  /// cheaper than one search over `reach`.
  Projection locate_growing(const Point3& p, int group, int start, double first_radius, double reach) const;
  /// Faces whose bounding boxes come within `radius` of p on every axis (a superset of the faces
  /// within `radius`), ascending, none repeated.
  void faces_near(const Point3& p, double radius, std::vector<int>& out) const;

  const Surface& surface() const { return surface_; }
  double cell() const { return cell_; }
  /// A length at the rounding level of the surface (1e-12 of its diagonal): search radii and
  /// distance ties use it, so that the result does not depend on the model's unit.
  double rounding_length() const { return rounding_length_; }

private:
  using Key = std::int64_t;
  Key key(long i, long j, long k) const;
  std::array<long, 3> cell_of(const Point3& p) const;
  bool accept(int f, int group, const Point3& normal) const;
  double consider_face(int f, const Point3& p, const Point3& normal, Projection& best) const;

  const Surface& surface_;
  double cell_;
  double rounding_length_;
  double mean_face_area_ = 0;
  Point3 origin_;
  std::unordered_map<Key, std::vector<int>> grid_;
  // Per face: its bounding box (min x, y, z, max x, y, z). A grid cell of a fine input holds
  // hundreds of faces, each tested against the query box.
  std::vector<std::array<double, 6>> face_box_;
  mutable std::vector<int> stamp_;  // per-face visit marks for the walk and the grid query
  mutable int stamp_value_ = 0;
};

}  // namespace mr::remesh
