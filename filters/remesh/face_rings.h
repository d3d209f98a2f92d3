// The faces around each point of a triangle list, in compressed rows: the faces of point v are
// item[begin[v]] .. item[begin[v + 1] - 1], in face order.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace mr::remesh {

struct FaceRings {
  std::vector<int> begin, item;

  FaceRings(size_t points, const std::vector<std::array<int, 3>>& faces) : begin(points + 1, 0) {
    for (const auto& f : faces) for (int v : f) begin[v + 1]++;
    for (size_t i = 1; i <= points; ++i) begin[i] += begin[i - 1];
    item.resize(begin[points]);
    std::vector<int> fill(begin.begin(), begin.end() - 1);
    for (size_t f = 0; f < faces.size(); ++f) for (int v : faces[f]) item[fill[v]++] = int(f);
  }
};

}  // namespace mr::remesh
