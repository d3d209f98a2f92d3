#include "shapes.h"

#include <cmath>
#include <map>

namespace mr::test {

void build(TriMesh& m, const std::vector<Point3>& points, const std::vector<std::array<int, 3>>& faces) {
  m.Clear();
  vcg::tri::Allocator<TriMesh>::AddVertices(m, points.size());
  vcg::tri::Allocator<TriMesh>::AddFaces(m, faces.size());
  for (size_t i = 0; i < points.size(); ++i) m.vert[i].P() = points[i];
  for (size_t i = 0; i < faces.size(); ++i)
    for (int z = 0; z < 3; ++z) m.face[i].V(z) = &m.vert[faces[i][z]];
  m.bbox.SetNull();
  for (const auto& v : m.vert) m.bbox.Add(v.cP());
}

namespace {
// Welds points on a lattice so shared cube edges get shared vertices.
struct Welder {
  std::map<std::array<long, 3>, int> index;
  std::vector<Point3> points;
  int add(const Point3& p) {
    std::array<long, 3> key = {std::lround(p[0] * 1e6), std::lround(p[1] * 1e6), std::lround(p[2] * 1e6)};
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    index[key] = int(points.size());
    points.push_back(p);
    return int(points.size()) - 1;
  }
};
}  // namespace

void cube(TriMesh& m, int n) {
  Welder w;
  std::vector<std::array<int, 3>> faces;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      int u = (axis + 1) % 3, v = (axis + 2) % 3;
      auto at = [&](int i, int j) {
        Point3 p;
        p[axis] = sign;
        p[u] = -1.0 + 2.0 * i / n;
        p[v] = -1.0 + 2.0 * j / n;
        return w.add(p);
      };
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
          if (sign > 0) { faces.push_back({a, b, c}); faces.push_back({a, c, d}); }
          else { faces.push_back({a, c, b}); faces.push_back({a, d, c}); }
        }
    }
  build(m, w.points, faces);
}

void cylinder(TriMesh& m, int segments, int rings, double radius, double height) {
  const double pi = 3.14159265358979323846;
  std::vector<Point3> pts;
  std::vector<std::array<int, 3>> faces;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s < segments; ++s) {
      double a = 2 * pi * s / segments;
      pts.push_back(Point3(radius * std::cos(a), radius * std::sin(a), -height / 2 + height * r / rings));
    }
  auto id = [&](int r, int s) { return r * segments + (s % segments); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      faces.push_back({id(r, s), id(r, s + 1), id(r + 1, s + 1)});
      faces.push_back({id(r, s), id(r + 1, s + 1), id(r + 1, s)});
    }
  int bottom = int(pts.size());
  pts.push_back(Point3(0, 0, -height / 2));
  int top = int(pts.size());
  pts.push_back(Point3(0, 0, height / 2));
  for (int s = 0; s < segments; ++s) {
    faces.push_back({bottom, id(0, s + 1), id(0, s)});
    faces.push_back({top, id(rings, s), id(rings, s + 1)});
  }
  build(m, pts, faces);
}

void sphere(TriMesh& m, int subdivisions) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Point3> pts = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                             {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11},
                                           {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                           {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9},
                                           {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (auto& p : pts) p.Normalize();
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      Point3 p = (pts[a] + pts[b]) / 2.0;
      p.Normalize();
      pts.push_back(p);
      return mid[key] = int(pts.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (auto& f : faces) {
      int ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    faces.swap(next);
  }
  build(m, pts, faces);
}

void grid(TriMesh& m, int n) {
  std::vector<Point3> pts;
  std::vector<std::array<int, 3>> faces;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) pts.push_back(Point3(double(i) / n, double(j) / n, 0));
  auto id = [&](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  build(m, pts, faces);
}

}  // namespace mr::test
