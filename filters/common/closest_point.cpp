#include "common/closest_point.h"

namespace mr {

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

}  // namespace mr
