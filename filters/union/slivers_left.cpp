#include "union/slivers_left.h"

#include "union/triangle_angles.h"

#include <algorithm>

namespace mr::surface_union {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

std::vector<int> find_slivers_left(const Result& r, const std::vector<Body>& bodies, double angle_deg) {
  const double limit = angle_deg * kPi / 180;
  // Where each body's faces start in the sources' numbering; only the sources of the few
  // output slivers are measured (the input can have a million faces).
  std::vector<size_t> first{0};
  for (const Body& b : bodies) first.push_back(first.back() + b.faces.size());
  auto input_angle = [&](size_t s) {
    const size_t body = size_t(std::upper_bound(first.begin(), first.end(), s) - first.begin()) - 1;
    const Body& b = bodies[body];
    const auto& t = b.faces[s - first[body]];
    return smallest_angle(b.vertices[t[0]], b.vertices[t[1]], b.vertices[t[2]]);
  };
  std::vector<int> left;
  for (size_t f = 0; f < r.faces.size(); ++f) {
    const auto& t = r.faces[f];
    const double a = smallest_angle(r.vertices[t[0]], r.vertices[t[1]], r.vertices[t[2]]);
    if (!(a < limit)) continue;
    const int s = f < r.face_source.size() ? r.face_source[f] : -1;
    // (No source: nothing to excuse the face.)
    if (s < 0 || size_t(s) >= first.back() || a < input_angle(size_t(s))) left.push_back(int(f));
  }
  return left;
}

}  // namespace mr::surface_union
