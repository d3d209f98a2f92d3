// Small 3D and 2D geometric predicates the remesher needs: closest point on a
// triangle, triangle angles, and segment crossing in a tangent plane.
#pragma once

#include "common/closest_point.h"
#include "common/tri_mesh.h"

#include <array>
#include <vector>

namespace mr::remesh {

using mr::closest_point_on_triangle;

/// Angle (radians) at o of the corner o, p, q (0 when a side has no length).
inline double corner_angle(const Point3& o, const Point3& p, const Point3& q) {
  const Point3 u = p - o, v = q - o;
  if (u.Norm() == 0 || v.Norm() == 0) return 0.0;
  return std::atan2((u ^ v).Norm(), u * v);
}

/// Smallest interior angle of triangle (a,b,c) in radians (0 for a degenerate one).
double min_angle(const Point3& a, const Point3& b, const Point3& c);

/// The same for face f of a triangle list over `points`.
inline double min_angle(const std::vector<Point3>& points, const std::array<int, 3>& f) {
  return min_angle(points[f[0]], points[f[1]], points[f[2]]);
}

/// Unit normal of (a,b,c) by the right-hand rule, zero if degenerate.
Point3 unit_normal(const Point3& a, const Point3& b, const Point3& c);

/// A 2D frame in the tangent plane with normal n, origin o: (x,y) = ((p-o).e1, (p-o).e2).
struct TangentFrame {
  Point3 origin, e1, e2, normal;
  /// e1 along `direction` projected into the plane of `normal` (both need not be unit).
  TangentFrame(const Point3& origin, const Point3& direction, const Point3& normal);
  vcg::Point2d to_2d(const Point3& p) const;
};

/// Twice the signed area of 2D triangle (a,b,c): > 0 when c is left of a->b.
inline double orient_2d(const vcg::Point2d& a, const vcg::Point2d& b, const vcg::Point2d& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/// True if the open 2D segments pq and rs cross (touching at an end point does not count;
/// collinear overlap does). `eps` is an area tolerance (squared length units).
bool segments_cross_2d(const vcg::Point2d& p, const vcg::Point2d& q, const vcg::Point2d& r,
                       const vcg::Point2d& s, double eps);

/// True if 2D point p lies strictly inside triangle (a,b,c) (any orientation), by more than eps area.
bool strictly_inside_2d(const vcg::Point2d& p, const vcg::Point2d& a, const vcg::Point2d& b,
                        const vcg::Point2d& c, double eps);

}  // namespace mr::remesh
