// All bodies of a union run in one indexed triangle soup.
#pragma once

#include <array>
#include <vector>

namespace mr::surface_union {

struct Soup {
  std::vector<std::array<double, 3>> vertex;
  std::vector<std::array<int, 3>> face;  ///< vertex indices, outward oriented
  std::vector<int> body;                 ///< body of each face
  int body_count = 0;
};

/// What the intersections put into one face: constraint segments and isolated
/// points (as point-table indices), and the faces of other bodies lying in its plane.
struct FaceConstraints {
  std::vector<std::array<int, 2>> segments;
  std::vector<int> points;
  std::vector<int> coplanar;
};

}  // namespace mr::surface_union
