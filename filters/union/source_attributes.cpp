#include "union/source_attributes.h"

#include "common/closest_point.h"
#include "common/errors.h"

#include <algorithm>
#include <optional>

namespace mr::surface_union {

namespace {

/// First face index of each body in the concatenation of all bodies' faces, and the total.
std::vector<int> face_offsets(const std::vector<Body>& bodies) {
  std::vector<int> first(bodies.size() + 1, 0);
  for (size_t b = 0; b < bodies.size(); ++b) first[b + 1] = first[b] + int(bodies[b].faces.size());
  return first;
}

FaceOrigin origin_of(int source, const std::vector<int>& first) {
  const int b = int(std::upper_bound(first.begin(), first.end(), source) - first.begin()) - 1;
  return {b, source - first[size_t(b)]};
}

/// Faces at each vertex of one body, in flat arrays; built when the body is first asked.
struct BodyStars {
  std::vector<int> first, faces;
  explicit BodyStars(const Body& b) : first(b.vertices.size() + 1, 0) {
    for (const auto& t : b.faces)
      for (int v : t) ++first[size_t(v) + 1];
    for (size_t v = 0; v < b.vertices.size(); ++v) first[v + 1] += first[v];
    faces.resize(size_t(first.back()));
    std::vector<int> next(first.begin(), first.end() - 1);
    for (int f = 0; f < int(b.faces.size()); ++f)
      for (int v : b.faces[size_t(f)]) faces[size_t(next[size_t(v)]++)] = f;
  }
};

class Locator {
public:
  explicit Locator(const std::vector<Body>& bodies) : bodies_(bodies), stars_(bodies.size()) {}

  /// The face of `start`'s body nearest to p, walking from `start` to the neighbour (through
  /// a shared corner) nearest to p while that gets nearer: the sliver step moves faces along
  /// the surface, so a face's slot may have come from a face a few rings away. The walk
  /// stays on the start's sheet (a plate's other side, as near in space, is never entered
  /// unless nearer through the surface).
  PointOrigin locate(FaceOrigin start, const std::array<double, 3>& p, double* squared_distance = nullptr) {
    const Body& b = bodies_[size_t(start.body)];
    if (!stars_[size_t(start.body)]) stars_[size_t(start.body)].emplace(b);
    const BodyStars& stars = *stars_[size_t(start.body)];
    std::array<double, 3> bary{};
    double d = distance(b, start.face, p, bary);
    // A point in the face (rounding off it) ends the walk at once: most faces are where
    // they were cut.
    const double in_face = 1e-18 * longest_edge_squared(b, start.face);
    for (int steps = 0; steps < kMaxSteps && d > in_face; ++steps) {
      int best = -1;
      double best_d = d;
      std::array<double, 3> best_bary{};
      for (int v : b.faces[size_t(start.face)])
        for (int k = stars.first[size_t(v)]; k < stars.first[size_t(v) + 1]; ++k) {
          const int h = stars.faces[size_t(k)];
          std::array<double, 3> hb{};
          const double dh = distance(b, h, p, hb);
          if (dh < best_d) { best_d = dh; best = h; best_bary = hb; }
        }
      if (best < 0) break;
      start.face = best;
      d = best_d;
      bary = best_bary;
    }
    if (squared_distance) *squared_distance = d;
    double sum = 0;
    for (double& w : bary) sum += (w = std::max(0.0, w));
    for (double& w : bary) w = sum > 0 ? w / sum : 1.0 / 3;
    return {start, bary};
  }

private:
  static constexpr int kMaxSteps = 1000;  // (each step gets strictly nearer: a bound, not a limit met)
  static double longest_edge_squared(const Body& b, int f) {
    const auto& t = b.faces[size_t(f)];
    double l = 0;
    for (int z = 0; z < 3; ++z) {
      const auto& p = b.vertices[size_t(t[size_t(z)])];
      const auto& q = b.vertices[size_t(t[size_t((z + 1) % 3)])];
      l = std::max(l, (p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
    }
    return l;
  }
  static double distance(const Body& b, int f, const std::array<double, 3>& p, std::array<double, 3>& bary) {
    const auto& t = b.faces[size_t(f)];
    auto pt = [&](int z) {
      const auto& q = b.vertices[size_t(t[size_t(z)])];
      return Point3(q[0], q[1], q[2]);
    };
    const Point3 x(p[0], p[1], p[2]);
    return (closest_point_on_triangle(x, pt(0), pt(1), pt(2), bary) - x).SquaredNorm();
  }
  const std::vector<Body>& bodies_;
  std::vector<std::optional<BodyStars>> stars_;
};

std::array<double, 3> centroid(const Result& r, size_t f) {
  std::array<double, 3> g{0, 0, 0};
  for (int v : r.faces[f])
    for (int k = 0; k < 3; ++k) g[size_t(k)] += r.vertices[size_t(v)][size_t(k)] / 3;
  return g;
}

/// Each face's source, checked against the bodies: the face it was cut from.
std::vector<FaceOrigin> cut_from(const Result& r, const std::vector<Body>& bodies) {
  if (r.face_source.size() != r.faces.size())
    throw InvalidInput("the union result carries no face sources (it was not made by compute_union)");
  const std::vector<int> first = face_offsets(bodies);
  std::vector<FaceOrigin> out(r.faces.size());
  for (size_t f = 0; f < r.faces.size(); ++f) {
    const int s = r.face_source[f];
    if (s < 0 || s >= first.back()) throw InvalidInput("the union result does not come from these bodies");
    out[f] = origin_of(s, first);
  }
  return out;
}

std::vector<FaceOrigin> located_faces(const Result& r, const std::vector<Body>& bodies, Locator& locator) {
  std::vector<FaceOrigin> out = cut_from(r, bodies);
  for (size_t f = 0; f < r.faces.size(); ++f) out[f] = locator.locate(out[f], centroid(r, f)).face;
  return out;
}

}  // namespace

std::vector<int> face_bodies(const Result& r, const std::vector<Body>& bodies) {
  const std::vector<FaceOrigin> faces = cut_from(r, bodies);
  std::vector<int> out(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) out[f] = faces[f].body;
  return out;
}

std::vector<FaceOrigin> face_origins(const Result& r, const std::vector<Body>& bodies) {
  Locator locator(bodies);
  return located_faces(r, bodies, locator);
}

std::vector<PointOrigin> vertex_origins(const Result& r, const std::vector<Body>& bodies) {
  Locator locator(bodies);
  const std::vector<FaceOrigin> faces = located_faces(r, bodies, locator);
  auto corner_at = [&](const FaceOrigin& o, const std::array<double, 3>& p) {
    const auto& b = bodies[size_t(o.body)];
    const auto& t = b.faces[size_t(o.face)];
    for (int z = 0; z < 3; ++z)
      if (b.vertices[size_t(t[size_t(z)])] == p) return z;
    return -1;
  };
  // An input vertex at the vertex's place, seen from any of its faces' sources, first.
  std::vector<PointOrigin> out(r.vertices.size());
  std::vector<char> exact(r.vertices.size(), 0);
  for (size_t f = 0; f < r.faces.size(); ++f)
    for (int v : r.faces[f]) {
      if (exact[size_t(v)]) continue;
      const int z = corner_at(faces[f], r.vertices[size_t(v)]);
      if (z < 0) continue;
      out[size_t(v)].face = faces[f];
      out[size_t(v)].weight = {0, 0, 0};
      out[size_t(v)].weight[size_t(z)] = 1;
      exact[size_t(v)] = 1;
    }
  // Else the nearest point on the bodies of its faces, each walked to from the vertex's
  // first face of that body: a vertex on an intersection line may have been moved onto one
  // body's crease, off the other body (within the sliver step's bound of the union).
  std::vector<double> nearest(r.vertices.size(), -1);
  std::vector<std::vector<int>> bodies_tried(r.vertices.size());
  for (size_t f = 0; f < r.faces.size(); ++f)
    for (int v : r.faces[f]) {
      if (exact[size_t(v)]) continue;
      auto& tried = bodies_tried[size_t(v)];
      if (std::find(tried.begin(), tried.end(), faces[f].body) != tried.end()) continue;
      tried.push_back(faces[f].body);
      double d = 0;
      const PointOrigin o = locator.locate(faces[f], r.vertices[size_t(v)], &d);
      if (nearest[size_t(v)] < 0 || d < nearest[size_t(v)]) {
        nearest[size_t(v)] = d;
        out[size_t(v)] = o;
      }
    }
  return out;
}

}  // namespace mr::surface_union
