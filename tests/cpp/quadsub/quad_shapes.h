// Quad nets shared by the quad subdivision tests.
#pragma once

#include "quadsub/quad_mesh.h"

#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace mr::quadsub::test {

constexpr double kPi = 3.14159265358979323846;

/// Regular n x n quads on [x0, x0 + 1] x [0, 1] with z = f(x, y).
template <class F>
QuadMesh grid(int n, F f, double x0 = 0) {
  QuadMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = x0 + double(i) / n, y = double(j) / n;
      m.points.push_back(Point3(x, y, f(x, y)));
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      m.quads.push_back({a, a + 1, a + n + 2, a + n + 1});
    }
  return m;
}

/// n sectors of k x k quads glued around one centre vertex (vertex 0) of valence n, flat (z = 0).
inline QuadMesh sector_fan(int n, int k) {
  QuadMesh m;
  std::map<std::pair<int, std::pair<int, int>>, int> index;  // (sector, (a, b)) -> vertex
  auto vertex = [&](int s, int a, int b) {
    // a lattice point on a sector border belongs to the neighbouring sector as well
    if (a == 0 && b == 0) s = 0;
    else if (a == 0) { s = (s + 1) % n; a = b; b = 0; }
    const auto key = std::make_pair(s, std::make_pair(a, b));
    const auto it = index.find(key);
    if (it != index.end()) return it->second;
    const double t0 = 2 * kPi * s / n, t1 = 2 * kPi * (s + 1) / n;
    m.points.push_back(Point3(a * std::cos(t0) + b * std::cos(t1), a * std::sin(t0) + b * std::sin(t1), 0));
    return index[key] = int(m.points.size()) - 1;
  };
  for (int s = 0; s < n; ++s)
    for (int a = 0; a < k; ++a)
      for (int b = 0; b < k; ++b)
        m.quads.push_back({vertex(s, a, b), vertex(s, a + 1, b), vertex(s, a + 1, b + 1), vertex(s, a, b + 1)});
  return m;
}

/// The quads as polygons (the subdivision's input form).
inline std::vector<std::vector<int>> polygons(const QuadMesh& m) {
  std::vector<std::vector<int>> out;
  for (const auto& q : m.quads) out.push_back({q[0], q[1], q[2], q[3]});
  return out;
}

}  // namespace mr::quadsub::test
