#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <cmath>

namespace mr::remesh {

double min_angle(const Point3& a, const Point3& b, const Point3& c) {
  return std::min({corner_angle(a, b, c), corner_angle(b, c, a), corner_angle(c, a, b)});
}

Point3 unit_normal(const Point3& a, const Point3& b, const Point3& c) {
  Point3 n = (b - a) ^ (c - a);
  const double len = n.Norm();
  return len > 0 ? n / len : Point3(0, 0, 0);
}

TangentFrame::TangentFrame(const Point3& o, const Point3& direction, const Point3& n) : origin(o) {
  normal = n;
  const double nn = normal.Norm();
  normal = nn > 0 ? normal / nn : Point3(0, 0, 1);
  e1 = direction - normal * (direction * normal);
  if (e1.Norm() == 0) e1 = std::abs(normal[0]) < 0.9 ? Point3(1, 0, 0) ^ normal : Point3(0, 1, 0) ^ normal;
  e1.Normalize();
  e2 = normal ^ e1;
}

vcg::Point2d TangentFrame::to_2d(const Point3& p) const {
  const Point3 d = p - origin;
  return vcg::Point2d(d * e1, d * e2);
}

bool segments_cross_2d(const vcg::Point2d& p, const vcg::Point2d& q, const vcg::Point2d& r,
                       const vcg::Point2d& s, double eps) {
  const double o1 = orient_2d(p, q, r), o2 = orient_2d(p, q, s);
  const double o3 = orient_2d(r, s, p), o4 = orient_2d(r, s, q);
  if (((o1 > eps && o2 < -eps) || (o1 < -eps && o2 > eps)) &&
      ((o3 > eps && o4 < -eps) || (o3 < -eps && o4 > eps)))
    return true;
  // Collinear overlap: both of r,s on the line pq and the intervals overlap in their interiors.
  if (std::abs(o1) <= eps && std::abs(o2) <= eps) {
    const vcg::Point2d d = q - p;
    const double len2 = d.SquaredNorm();
    if (len2 == 0) return false;
    double t0 = ((r - p) * d) / len2, t1 = ((s - p) * d) / len2;
    if (t0 > t1) std::swap(t0, t1);
    return t1 > 1e-9 && t0 < 1 - 1e-9 && std::min(t1, 1.0) - std::max(t0, 0.0) > 1e-9;
  }
  return false;
}

bool strictly_inside_2d(const vcg::Point2d& p, const vcg::Point2d& a, const vcg::Point2d& b,
                        const vcg::Point2d& c, double eps) {
  double s = orient_2d(a, b, c) >= 0 ? 1.0 : -1.0;
  return s * orient_2d(a, b, p) > eps && s * orient_2d(b, c, p) > eps && s * orient_2d(c, a, p) > eps;
}

}  // namespace mr::remesh
