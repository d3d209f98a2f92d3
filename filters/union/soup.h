// All bodies of a union run in one indexed triangle soup.
#pragma once

#include <array>
#include <cstddef>
#include <deque>
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

/// The constraints of the faces that were cut, by soup face: a slot per face instead of
/// a hash map (a quarter of a million cut faces in the big clusters). References stay
/// valid while faces are added (a deque), so two faces' constraints can be filled at once.
class CutFaces {
public:
  explicit CutFaces(size_t face_count) : slot_(face_count, -1) {}
  FaceConstraints& operator[](int f) {
    int& s = slot_[f];
    if (s < 0) {
      s = int(faces_.size());
      faces_.emplace_back();
    }
    return faces_[s];
  }
  const FaceConstraints* find(int f) const { return slot_[f] < 0 ? nullptr : &faces_[slot_[f]]; }
  size_t size() const { return faces_.size(); }

private:
  std::vector<int> slot_;
  std::deque<FaceConstraints> faces_;
};

}  // namespace mr::surface_union
