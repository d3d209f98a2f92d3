#include "union/same_cover.h"

#include <cmath>

#include "union/exact.h"

namespace mr::surface_union {

namespace {

struct Corner {
  int id;
  V3 at;
  bool operator==(const Corner& o) const { return id == o.id && at == o.at; }
};

struct Edge {
  Corner from, to;
  bool operator==(const Edge& o) const { return from == o.from && to == o.to; }
};

constexpr int kMaxPlanes = 4;  // a star at a CAD corner has three

/// Faces lying exactly in one plane, with the directed sides of the old and the new ones.
struct Plane {
  int axis = -1;     // the plane is x[axis] = value (CAD), or -1: the one plane of all faces
  double value = 0;
  int i = 0, j = 1;  // a projection in which the plane maps one to one
  int sign = 0;      // how every face turns in that projection
  std::vector<Edge> sides[2];  // of the old faces, of the new ones
};

/// The plane of face f among `planes`, added if new; nullptr when there are too many
/// or the face is degenerate or turns against the others of its plane. With `general`
/// every face is taken to lie in the one plane of the first (checked by the caller).
Plane* plane_of(const PlacedFace& f, bool general, std::vector<Plane>& planes) {
  const int k = general ? -1 : axis_plane(f.at.data());
  Plane* found = nullptr;
  for (Plane& p : planes)
    if (general || (p.axis == k && p.value == f.at[0][k])) {
      found = &p;
      break;
    }
  if (!found) {
    if (int(planes.size()) == kMaxPlanes) return nullptr;
    Plane p;
    p.axis = k;
    p.value = k >= 0 ? f.at[0][k] : 0;
    const int n_axis = k >= 0 ? k : largest_normal_axis(f.at.data());
    p.i = (n_axis + 1) % 3;
    p.j = (n_axis + 2) % 3;
    planes.push_back(std::move(p));
    found = &planes.back();
  }
  const int s = orient2d(f.at[0].data(), f.at[1].data(), f.at[2].data(), found->i, found->j);
  if (s == 0 || (found->sign != 0 && s != found->sign)) return nullptr;
  found->sign = s;
  return found;
}

/// Every corner of every face lies exactly in the plane of `ref`. Stops at the first
/// that does not (curved stars, where the filter tells at once).
bool all_in_plane(const PlacedFace& ref, const std::vector<PlacedFace>& faces) {
  for (const PlacedFace& f : faces)
    for (const V3& p : f.at)
      if (orient3d(ref.at[0].data(), ref.at[1].data(), ref.at[2].data(), p.data()) != 0) return false;
  return true;
}

/// Removes the pairs of opposite sides (inside the faces' union) from `sides`.
void drop_inner_sides(std::vector<Edge>& sides) {
  for (size_t a = 0; a < sides.size(); ++a)
    for (size_t b = a + 1; b < sides.size(); ++b)
      if (sides[a].from == sides[b].to && sides[a].to == sides[b].from) {
        sides.erase(sides.begin() + long(b));
        sides.erase(sides.begin() + long(a));
        --a;
        break;
      }
}

/// The sides as one directed path (its corners in order), or false.
bool as_path(const std::vector<Edge>& sides, std::vector<Corner>& path) {
  path.clear();
  const Edge* first = nullptr;
  for (const Edge& e : sides) {
    bool has_pred = false;
    for (const Edge& o : sides) has_pred |= o.to == e.from;
    if (!has_pred) {
      if (first) return false;  // two starts
      first = &e;
    }
  }
  if (!first) return false;  // a closed loop
  path.push_back(first->from);
  path.push_back(first->to);
  for (size_t n = 1; n < sides.size(); ++n) {
    const Edge* next = nullptr;
    int choices = 0;
    for (const Edge& e : sides)
      if (e.from == path.back()) {
        next = &e;
        ++choices;
      }
    if (choices != 1) return false;
    path.push_back(next->to);
  }
  return true;
}

/// Every corner of `path` lies on the straight segment from its first to its last
/// corner, in order (exact, in the plane's projection).
bool straight_run(const std::vector<Corner>& path, const Plane& p) {
  const V3& s = path.front().at;
  const V3& e = path.back().at;
  const int m = std::fabs(e[p.i] - s[p.i]) >= std::fabs(e[p.j] - s[p.j]) ? p.i : p.j;
  const double dir = e[m] > s[m] ? 1 : -1;
  if (e[m] == s[m]) return false;
  for (size_t t = 1; t < path.size(); ++t) {
    if (!(dir * (path[t].at[m] - path[t - 1].at[m]) > 0)) return false;
    if (t + 1 < path.size() && orient2d(s.data(), e.data(), path[t].at.data(), p.i, p.j) != 0) return false;
  }
  return true;
}

}  // namespace

int axis_plane(const V3 t[3]) {
  for (int k = 0; k < 3; ++k)
    if (t[0][k] == t[1][k] && t[0][k] == t[2][k]) return k;
  return -1;
}

bool same_cover(const std::vector<PlacedFace>& before, const std::vector<PlacedFace>& after) {
  if (before.empty()) return false;
  // Faces across coordinate axes (CAD plates) fall into up to four planes; otherwise all
  // must lie in one plane (a flat star elsewhere).
  bool general = false;
  for (int side = 0; side < 2 && !general; ++side)
    for (const PlacedFace& f : side == 0 ? before : after)
      if (axis_plane(f.at.data()) < 0) {
        general = true;
        break;
      }
  if (general && !(all_in_plane(before[0], before) && all_in_plane(before[0], after))) return false;
  std::vector<Plane> planes;
  planes.reserve(kMaxPlanes);
  for (int side = 0; side < 2; ++side)
    for (const PlacedFace& f : side == 0 ? before : after) {
      Plane* p = plane_of(f, general, planes);
      if (!p) return false;
      for (int z = 0; z < 3; ++z)
        p->sides[side].push_back({{f.id[z], f.at[z]}, {f.id[(z + 1) % 3], f.at[(z + 1) % 3]}});
    }
  std::vector<Corner> old_path, new_path;
  for (Plane& p : planes) {
    auto& old_sides = p.sides[0];
    auto& new_sides = p.sides[1];
    drop_inner_sides(old_sides);
    drop_inner_sides(new_sides);
    // Sides both boundaries have.
    for (size_t a = 0; a < old_sides.size(); ++a)
      for (size_t b = 0; b < new_sides.size(); ++b)
        if (old_sides[a] == new_sides[b]) {
          old_sides.erase(old_sides.begin() + long(a));
          new_sides.erase(new_sides.begin() + long(b));
          --a;
          break;
        }
    if (old_sides.empty() && new_sides.empty()) continue;
    // What differs must be one straight run, from the same corner to the same corner.
    if (!as_path(old_sides, old_path) || !as_path(new_sides, new_path)) return false;
    if (!(old_path.front() == new_path.front()) || !(old_path.back() == new_path.back())) return false;
    if (!straight_run(old_path, p) || !straight_run(new_path, p)) return false;
  }
  return true;
}

}  // namespace mr::surface_union
