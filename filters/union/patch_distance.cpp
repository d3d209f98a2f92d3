#include "union/patch_distance.h"

#include "union/triangle_distance.h"

namespace mr::surface_union {
namespace {

// `hint`: the face that held the previous sample, tried first (samples of one face are
// mostly near the same face).
bool near_some_face(const V3& p, const std::vector<PreparedTriangle>& faces, double limit2, size_t& hint) {
  auto near = [&](size_t i) { return faces[i].squared_distance(p) <= limit2; };
  if (hint < faces.size() && near(hint)) return true;
  for (size_t i = 0; i < faces.size(); ++i)
    if (i != hint && near(i)) {
      hint = i;
      return true;
    }
  return false;
}

bool samples_within(const std::vector<Triangle>& from, const std::vector<Triangle>& to_faces, double limit2) {
  std::vector<PreparedTriangle> to;
  to.reserve(to_faces.size());
  for (const Triangle& t : to_faces) to.emplace_back(t[0], t[1], t[2]);
  size_t hint = 0;
  for (const Triangle& t : from) {
    V3 g;
    for (int k = 0; k < 3; ++k) g[k] = (t[0][k] + t[1][k] + t[2][k]) / 3;
    if (!near_some_face(g, to, limit2, hint)) return false;
    for (int z = 0; z < 3; ++z) {
      V3 mid;
      for (int k = 0; k < 3; ++k) mid[k] = (t[z][k] + t[(z + 1) % 3][k]) / 2;
      if (!near_some_face(mid, to, limit2, hint)) return false;
    }
  }
  return true;
}

// All corners of both patches have the same coordinate along one axis (CAD plates).
bool in_one_axis_plane(const std::vector<Triangle>& a, const std::vector<Triangle>& b) {
  if (a.empty()) return false;
  for (int k = 0; k < 3; ++k) {
    const double c = a[0][0][k];
    bool same = true;
    for (const auto* patch : {&a, &b})
      for (const Triangle& t : *patch)
        same = same && t[0][k] == c && t[1][k] == c && t[2][k] == c;
    if (same) return true;
  }
  return false;
}

}  // namespace

bool patches_within(const std::vector<Triangle>& a, const std::vector<Triangle>& b, double limit) {
  // Unfolded patches with one boundary in one plane cover the same polygon: the moves
  // turn no face over, so nothing is to be sampled there.
  if (in_one_axis_plane(a, b)) return true;
  const double limit2 = limit * limit;
  return samples_within(a, b, limit2) && samples_within(b, a, limit2);
}

}  // namespace mr::surface_union
