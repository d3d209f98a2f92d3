// Squared distance from points to one triangle, asked many times: the sliver step
// measures thousands of sample points against the cut's faces. The triangle's edges and
// their dot products are kept, so a query takes two dot products to find its Voronoi
// region (Ericson, "Real-Time Collision Detection", 5.1.5, rewritten on those products).
#pragma once

#include "union/vec3.h"

#include <algorithm>

namespace mr::surface_union {

class PreparedTriangle {
public:
  PreparedTriangle() = default;
  PreparedTriangle(const V3& a, const V3& b, const V3& c)
      : a_(a), ab_(sub3(b, a)), ac_(sub3(c, a)), d00_(dot(ab_, ab_)), d01_(dot(ab_, ac_)), d11_(dot(ac_, ac_)) {
    const V3 n = cross(ab_, ac_);
    const double len = norm(n);
    degenerate_ = !(len > 0);
    if (!degenerate_) unit_normal_ = {n[0] / len, n[1] / len, n[2] / len};
  }

  double squared_distance(const V3& p) const {
    const V3 ap = sub3(p, a_);
    // No interior (corners in a line or at one point): the regions' divisions would be
    // 0 / 0; the triangle is then the segment between its farthest corners.
    if (degenerate_)
      return std::min({on_segment(ap, {0, 0, 0}, ab_), on_segment(ap, {0, 0, 0}, ac_), on_segment(ap, ab_, ac_)});
    const double d1 = dot(ab_, ap), d2 = dot(ac_, ap);
    if (d1 <= 0 && d2 <= 0) return dot(ap, ap);  // corner a
    const double d3 = d1 - d00_, d4 = d2 - d01_;  // ab.(p-b), ac.(p-b)
    if (d3 >= 0 && d4 <= d3) return along(ap, ab_, 1, ac_, 0);  // corner b
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return along(ap, ab_, d1 / d00_, ac_, 0);  // side ab
    const double d5 = d1 - d01_, d6 = d2 - d11_;  // ab.(p-c), ac.(p-c)
    if (d6 >= 0 && d5 <= d6) return along(ap, ab_, 0, ac_, 1);  // corner c
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return along(ap, ab_, 0, ac_, d2 / d11_);  // side ac
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {  // side bc
      const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      return along(ap, ab_, 1 - w, ac_, w);
    }
    const double h = dot(unit_normal_, ap);  // inside: the distance from the plane
    return h * h;
  }

private:
  // From p (ap = p - a) to the segment from a + u to a + v.
  static double on_segment(const V3& ap, const V3& u, const V3& v) {
    const V3 d = sub3(v, u), up = sub3(ap, u);
    const double dd = dot(d, d);
    const double t = dd > 0 ? std::clamp(dot(up, d) / dd, 0.0, 1.0) : 0.0;
    const V3 e{up[0] - t * d[0], up[1] - t * d[1], up[2] - t * d[2]};
    return dot(e, e);
  }
  // |ap - u s - v t|^2: from p to the point a + u s + v t.
  static double along(const V3& ap, const V3& u, double s, const V3& v, double t) {
    const V3 d{ap[0] - u[0] * s - v[0] * t, ap[1] - u[1] * s - v[1] * t, ap[2] - u[2] * s - v[2] * t};
    return dot(d, d);
  }
  V3 a_{}, ab_{}, ac_{}, unit_normal_{};
  double d00_ = 0, d01_ = 0, d11_ = 0;
  bool degenerate_ = true;
};

}  // namespace mr::surface_union
