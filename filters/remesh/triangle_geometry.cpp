#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <cmath>

namespace mr::remesh {

// Ericson, "Real-Time Collision Detection", 5.1.5: Voronoi regions of the triangle.
Point3 closest_point_on_triangle(const Point3& p, const Point3& a, const Point3& b, const Point3& c,
                                 std::array<double, 3>& bary) {
  const Point3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab * ap, d2 = ac * ap;
  if (d1 <= 0 && d2 <= 0) { bary = {1, 0, 0}; return a; }
  const Point3 bp = p - b;
  const double d3 = ab * bp, d4 = ac * bp;
  if (d3 >= 0 && d4 <= d3) { bary = {0, 1, 0}; return b; }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    bary = {1 - v, v, 0};
    return a + ab * v;
  }
  const Point3 cp = p - c;
  const double d5 = ab * cp, d6 = ac * cp;
  if (d6 >= 0 && d5 <= d6) { bary = {0, 0, 1}; return c; }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    bary = {1 - w, 0, w};
    return a + ac * w;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    bary = {0, 1 - w, w};
    return b + (c - b) * w;
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) {  // degenerate triangle: fall back to the nearest corner
    const double da = (p - a).SquaredNorm(), db = (p - b).SquaredNorm(), dc = (p - c).SquaredNorm();
    if (da <= db && da <= dc) { bary = {1, 0, 0}; return a; }
    if (db <= dc) { bary = {0, 1, 0}; return b; }
    bary = {0, 0, 1};
    return c;
  }
  const double v = vb / sum, w = vc / sum;
  bary = {1 - v - w, v, w};
  return a + ab * v + ac * w;
}

double min_angle(const Point3& a, const Point3& b, const Point3& c) {
  auto angle = [](const Point3& o, const Point3& p, const Point3& q) {
    Point3 u = p - o, v = q - o;
    const double nu = u.Norm(), nv = v.Norm();
    if (nu == 0 || nv == 0) return 0.0;
    return std::atan2((u ^ v).Norm(), u * v);
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
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
