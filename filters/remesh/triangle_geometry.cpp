#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <cmath>

namespace mr::remesh {

double min_angle(const Point3& a, const Point3& b, const Point3& c) {
  // The angle at a corner is atan2(|u x v|, u.v), falling as the cotangent u.v / |u x v| rises:
  // only the corner with the largest cotangent, and any within rounding of it, needs the arc
  // tangent (a tenth of a remesh went to arc tangents). The result is the same value as the
  // smallest of corner_angle's three, bit for bit.
  const Point3* p[3] = {&a, &b, &c};
  double cross[3], dot[3], cot[3];
  for (int k = 0; k < 3; ++k) {
    const Point3 u = *p[(k + 1) % 3] - *p[k], v = *p[(k + 2) % 3] - *p[k];
    if (u.Norm() == 0 || v.Norm() == 0) return 0.0;
    cross[k] = (u ^ v).Norm();
    dot[k] = u * v;
    cot[k] = dot[k] / cross[k];
    if (!(cross[k] > 0) || !std::isfinite(cot[k]))  // flat or not finite: every corner measured
      return std::min({corner_angle(a, b, c), corner_angle(b, c, a), corner_angle(c, a, b)});
  }
  const double largest = std::max({cot[0], cot[1], cot[2]});
  // Cotangents closer than this share of the largest may order their computed angles either way.
  constexpr double kTie = 1e-9;
  double smallest = HUGE_VAL;
  for (int k = 0; k < 3; ++k)
    if (cot[k] >= largest - kTie * std::fabs(largest)) smallest = std::min(smallest, std::atan2(cross[k], dot[k]));
  return smallest;
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
