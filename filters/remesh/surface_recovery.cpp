#include "remesh/surface_recovery.h"

#include "remesh/triangle_geometry.h"

#include <cmath>
#include <cstdint>
#include <set>
#include <unordered_map>

namespace mr::remesh {

std::vector<std::array<Point3, 3>> corner_normals(const Surface& s) {
  std::unordered_map<std::uint64_t, Point3> sum;  // (vertex, group) -> area-weighted normal sum
  auto key = [](int v, int g) { return (std::uint64_t(std::uint32_t(v)) << 32) | std::uint32_t(g); };
  for (size_t f = 0; f < s.faces.size(); ++f) {
    const auto& t = s.faces[f];
    const Point3 n = (s.points[t[1]] - s.points[t[0]]) ^ (s.points[t[2]] - s.points[t[0]]);
    for (int v : t) {
      auto it = sum.emplace(key(v, s.group[f]), Point3(0, 0, 0)).first;
      it->second += n;
    }
  }
  std::vector<std::array<Point3, 3>> out(s.faces.size());
  for (size_t f = 0; f < s.faces.size(); ++f)
    for (int z = 0; z < 3; ++z) {
      Point3 n = sum[key(s.faces[f][z], s.group[f])];
      const double len = n.Norm();
      out[f][z] = len > 0 ? n / len : s.face_normal[f];
    }
  return out;
}

namespace {
// Normal component used by the Hermite/PN construction: w_ij = (x_j - x_i) . n_i.
double w(const Point3& xi, const Point3& xj, const Point3& ni) { return (xj - xi) * ni; }
}  // namespace

Point3 quadratic_point(const Surface& s, const std::vector<std::array<Point3, 3>>& normals, int f,
                       const std::array<double, 3>& l) {
  const auto& t = s.faces[f];
  const Point3 x[3] = {s.points[t[0]], s.points[t[1]], s.points[t[2]]};
  const auto& n = normals[f];
  Point3 p(0, 0, 0);
  for (int i = 0; i < 3; ++i) p += x[i] * (l[i] * (2 * l[i] - 1));
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    // Mid-point of the cubic Hermite curve between x_i and x_j with tangents in the normal planes.
    const Point3 mid = (x[i] + x[j]) * 0.5 - (n[i] * w(x[i], x[j], n[i]) + n[j] * w(x[j], x[i], n[j])) * 0.125;
    p += mid * (4 * l[i] * l[j]);
  }
  return p;
}

Point3 cubic_point(const Surface& s, const std::vector<std::array<Point3, 3>>& normals, int f,
                   const std::array<double, 3>& l) {
  const auto& t = s.faces[f];
  const Point3 x[3] = {s.points[t[0]], s.points[t[1]], s.points[t[2]]};
  const auto& n = normals[f];
  // Edge control points b_ij (the one next to corner i on side ij).
  auto b = [&](int i, int j) { return (x[i] * 2 + x[j] - n[i] * w(x[i], x[j], n[i])) / 3.0; };
  const Point3 b01 = b(0, 1), b10 = b(1, 0), b12 = b(1, 2), b21 = b(2, 1), b20 = b(2, 0), b02 = b(0, 2);
  const Point3 e = (b01 + b10 + b12 + b21 + b20 + b02) / 6.0;
  const Point3 v = (x[0] + x[1] + x[2]) / 3.0;
  const Point3 centre = e + (e - v) * 0.5;
  const double u0 = l[0], u1 = l[1], u2 = l[2];
  return x[0] * (u0 * u0 * u0) + x[1] * (u1 * u1 * u1) + x[2] * (u2 * u2 * u2) + b01 * (3 * u0 * u0 * u1) +
         b10 * (3 * u0 * u1 * u1) + b12 * (3 * u1 * u1 * u2) + b21 * (3 * u1 * u2 * u2) + b20 * (3 * u2 * u2 * u0) +
         b02 * (3 * u2 * u0 * u0) + centre * (6 * u0 * u1 * u2);
}

int recover_surface(OutputMesh& out, const Surface& s, Recovery mode) {
  if (mode == Recovery::Linear) return 0;
  const auto normals = mode == Recovery::ClosestVertex ? std::vector<std::array<Point3, 3>>{} : corner_normals(s);
  std::set<int> taken;  // input vertices already used by the closest-vertex mode
  int moved = 0;
  for (size_t v = 0; v < out.points.size(); ++v) {
    if (out.kind[v] != PointKind::Free || out.host[v] < 0) continue;
    const int f = out.host[v];
    const auto& t = s.faces[f];
    std::array<double, 3> l;
    closest_point_on_triangle(out.points[v], s.points[t[0]], s.points[t[1]], s.points[t[2]], l);
    // A degenerate host face has no barycentric coordinates: the point stays as it is.
    if (!(std::isfinite(l[0]) && std::isfinite(l[1]) && std::isfinite(l[2]))) continue;
    Point3 p = out.points[v];
    if (mode == Recovery::ClosestVertex) {
      int best = -1;
      double best_d = 1e300;
      for (int k = 0; k < 3; ++k) {
        const double d = (s.points[t[k]] - out.points[v]).SquaredNorm();
        if (d < best_d && !taken.count(t[k])) { best_d = d; best = t[k]; }
      }
      if (best < 0) continue;  // every corner taken: moving would merge two output points
      taken.insert(best);
      p = s.points[best];
    } else if (mode == Recovery::Quadratic) {
      p = quadratic_point(s, normals, f, l);
    } else {
      p = cubic_point(s, normals, f, l);
    }
    // Normals averaged over degenerate faces only are zero: whatever the formula makes of
    // them, a point that is not finite stays where it was.
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) continue;
    if ((p - out.points[v]).Norm() > 0) ++moved;
    out.points[v] = p;
  }
  return moved;
}

}  // namespace mr::remesh
