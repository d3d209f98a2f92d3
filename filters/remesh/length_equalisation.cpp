#include "remesh/length_equalisation.h"

#include "remesh/face_rings.h"
#include "remesh/point_stars.h"
#include "remesh/star_shape.h"
#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <tuple>
#include <utility>

namespace mr::remesh {

namespace {

// A collapse may leave the removed point this far (x its size) from the new faces.
constexpr double kCollapseDeviation = 0.05;
// New faces may not turn by more than acos(0.7) from the faces they replace.
constexpr double kFoldCos = 0.7;

class EdgeLengthMoves {
public:
  EdgeLengthMoves(OutputMesh& out, const std::unordered_set<std::uint64_t>& fixed, const SurfaceLocator& locator,
                  const SizeField& size, const std::vector<char>& movable, double floor)
      : out_(out), fixed_(fixed), locator_(locator), size_(size), movable_(movable), floor_(floor),
        stars_(out), h_(out.points.size()) {
    for (size_t v = 0; v < out.points.size(); ++v) h_[v] = size_at_point(out, locator, size, int(v));
  }

  int collapse_short() {
    // Shortest (relative to the size) first; ties by the points, so the order is deterministic.
    std::vector<std::tuple<double, int, int>> edges;
    for (const auto& t : out_.faces)
      for (int z = 0; z < 3; ++z) {
        const int a = t[z], b = t[(z + 1) % 3];
        if (a > b || !(removable(a) || removable(b))) continue;
        const double r = length(a, b) / h(a, b);
        if (r < kShortEdge) edges.emplace_back(r, a, b);
      }
    std::sort(edges.begin(), edges.end());
    int done = 0;
    for (const auto& [ratio, a, b] : edges) {
      (void)ratio;
      int f, g;
      if (!edge_faces(a, b, f, g)) continue;  // gone with an earlier collapse
      double best = -1;
      int remove = -1;
      for (const auto& [v, w] : {std::pair{a, b}, std::pair{b, a}}) {
        if (!removable(v)) continue;
        const double q = quality_after(v, w);
        if (q > best) best = q, remove = v;
      }
      if (remove < 0) continue;
      collapse(remove, remove == a ? b : a);
      ++done;
    }
    drop_dead_faces(out_);
    return done;
  }

  /// Splits long edges at their middle, longest first; new points are movable.
  int split_long(std::vector<char>& movable_out) {
    std::vector<std::tuple<double, int, int>> edges;
    for (const auto& t : out_.faces)
      for (int z = 0; z < 3; ++z) {
        const int a = t[z], b = t[(z + 1) % 3];
        if (a > b || !(movable_[a] || movable_[b])) continue;
        const double r = length(a, b) / h(a, b);
        if (r > kLongEdge) edges.emplace_back(-r, a, b);
      }
    std::sort(edges.begin(), edges.end());
    int done = 0;
    for (const auto& [ratio, a, b] : edges) {
      (void)ratio;
      if (split(a, b)) {
        movable_out.push_back(1);
        ++done;
      }
    }
    return done;
  }

private:
  OutputMesh& out_;
  const std::unordered_set<std::uint64_t>& fixed_;
  const SurfaceLocator& locator_;
  const SizeField& size_;
  const std::vector<char>& movable_;
  double floor_;
  PointStars stars_;
  std::vector<double> h_;               // size at each point

  bool removable(int v) const { return out_.kind[v] == PointKind::Free && movable_[v]; }
  double length(int a, int b) const { return (out_.points[a] - out_.points[b]).Norm(); }
  double h(int a, int b) const { return 0.5 * (h_[a] + h_[b]); }
  Point3 normal(const std::array<int, 3>& t) const {
    return unit_normal(out_.points[t[0]], out_.points[t[1]], out_.points[t[2]]);
  }

  // The two faces on edge a-b, when it is an inner edge of one patch and not a feature edge.
  bool edge_faces(int a, int b, int& f, int& g) const {
    f = g = -1;
    if (fixed_.count(OutputMesh::edge_key(a, b))) return false;
    for (int k : stars_.of(a)) {
      const auto& t = out_.faces[k];
      if (t[0] != b && t[1] != b && t[2] != b) continue;
      if (f < 0) f = k;
      else if (g < 0) g = k;
      else return false;
    }
    return g >= 0 && out_.face_patch[f] == out_.face_patch[g];
  }

  // Smallest angle of the faces after free point v moves onto w, or -1 when that is not allowed.
  double quality_after(int v, int w) const {
    int f, g;
    if (!edge_faces(v, w, f, g)) return -1;
    if (!stars_.link_condition(out_, v, w, {f, g})) return -1;
    double before = 1e9;
    for (int x : {v, w})
      for (int k : stars_.of(x)) before = std::min(before, min_angle(out_.points, out_.faces[k]));
    const double limit = std::min(before, floor_);
    const Point3& p = out_.points[w];
    double after = 1e9;
    std::vector<std::array<Point3, 3>> fan;
    for (int k : stars_.of(v)) {
      if (k == f || k == g) continue;
      const auto& t = out_.faces[k];
      std::array<Point3, 3> q;
      for (int z = 0; z < 3; ++z) q[z] = t[z] == v ? p : out_.points[t[z]];
      const double a = min_angle(q[0], q[1], q[2]);
      if (a < limit || unit_normal(q[0], q[1], q[2]) * normal(t) < kFoldCos) return -1;
      after = std::min(after, a);
      fan.push_back(q);
    }
    // v was on the input: the faces that now cover its place stay close to where it was.
    double deviation = 1e300;
    for (const auto& q : fan) {
      std::array<double, 3> bary;
      deviation = std::min(deviation, (closest_point_on_triangle(out_.points[v], q[0], q[1], q[2], bary) - out_.points[v]).Norm());
    }
    if (fan.empty() || deviation > kCollapseDeviation * h_[v]) return -1;
    for (int u : stars_.neighbours(out_, v))
      if (u != w && length(w, u) > kLongEdge * h(w, u)) return -1;
    return after;
  }

  void collapse(int v, int w) {
    int f, g;
    edge_faces(v, w, f, g);
    stars_.collapse(out_, v, w, {f, g});
  }

  // Splits inner edge a-b at its middle (on the input) when the four new faces stay above
  // min(the old two's smallest angle, floor), turn with them and have no edge out of range.
  bool split(int a, int b) {
    int f, g;
    if (!edge_faces(a, b, f, g)) return false;
    auto runs = [&](int k, int x, int y) {
      const auto& t = out_.faces[k];
      for (int z = 0; z < 3; ++z)
        if (t[z] == x && t[(z + 1) % 3] == y) return true;
      return false;
    };
    if (!runs(f, a, b)) std::swap(f, g);
    if (!runs(f, a, b) || !runs(g, b, a)) return false;
    auto third = [&](int k) {
      for (int u : out_.faces[k])
        if (u != a && u != b) return u;
      return -1;
    };
    const int c = third(f), d = third(g);
    const Point3 nf = normal(out_.faces[f]), ng = normal(out_.faces[g]);
    Point3 n = nf + ng;
    const int start = out_.host[a] >= 0 ? out_.host[a] : out_.host[b];
    if (!(n.Norm() > 0) || start < 0) return false;
    n.Normalize();
    const Projection pr = locator_.locate((out_.points[a] + out_.points[b]) * 0.5, out_.face_patch[f], n, start, length(a, b));
    if (pr.face < 0) return false;
    const Point3 m = pr.point;
    const double hm = size_.at(pr.face, pr.bary);
    const double limit = std::min({min_angle(out_.points, out_.faces[f]), min_angle(out_.points, out_.faces[g]), floor_});
    const std::array<Point3, 3> q[4] = {{out_.points[a], m, out_.points[c]}, {m, out_.points[b], out_.points[c]},
                                        {out_.points[b], m, out_.points[d]}, {m, out_.points[a], out_.points[d]}};
    for (int k = 0; k < 4; ++k) {
      if (min_angle(q[k][0], q[k][1], q[k][2]) < limit) return false;
      if (unit_normal(q[k][0], q[k][1], q[k][2]) * (k < 2 ? nf : ng) < kFoldCos) return false;
    }
    for (int u : {a, b, c, d}) {
      const double r = (out_.points[u] - m).Norm() / (0.5 * (h_[u] + hm));
      if (r < kShortEdge || r > kLongEdge) return false;
    }
    const int v = out_.add_point(m, pr.face, PointKind::Free);
    h_.push_back(hm);
    stars_.add_point();
    const int f2 = int(out_.faces.size()), g2 = f2 + 1;
    out_.faces[f] = {a, v, c};
    out_.faces[g] = {b, v, d};
    out_.faces.push_back({v, b, c});
    out_.faces.push_back({v, a, d});
    out_.face_patch.push_back(out_.face_patch[f]);
    out_.face_patch.push_back(out_.face_patch[g]);
    stars_.drop_face(b, f);
    stars_.drop_face(a, g);
    stars_.of(b).push_back(f2);
    stars_.of(c).push_back(f2);
    stars_.of(a).push_back(g2);
    stars_.of(d).push_back(g2);
    stars_.of(v) = {f, g, f2, g2};
    return true;
  }
};

}  // namespace

int relax_edge_lengths(OutputMesh& out, const SurfaceLocator& locator, const SizeField& size,
                       const std::vector<char>& movable, double floor) {
  const size_t nv = out.points.size();
  const FaceRings rings(nv, out.faces);
  const std::vector<int>&begin = rings.begin, &ring = rings.item;
  const Surface& s = locator.surface();
  int moves = 0;
  std::vector<int> nb;
  for (size_t v = 0; v < nv; ++v) {
    if (out.kind[v] != PointKind::Free || !movable[v] || begin[v] == begin[v + 1] || out.host[v] < 0) continue;
    const double h = size_at_point(out, locator, size, int(v));
    nb.clear();
    for (int k = begin[v]; k < begin[v + 1]; ++k)
      for (int u : out.faces[ring[k]])
        if (u != int(v) && std::find(nb.begin(), nb.end(), u) == nb.end()) nb.push_back(u);
    // Edges out of range at p, and their squared distance from the size.
    auto misfit = [&](const Point3& p) {
      int n = 0;
      double err = 0;
      for (int u : nb) {
        const double l = (out.points[u] - p).Norm() / h;
        n += l < kShortEdge || l > kLongEdge;
        err += (l - 1) * (l - 1);
      }
      return std::make_pair(n, err);
    };
    const auto before_fit = misfit(out.points[v]);
    if (before_fit.first == 0) continue;
    // Each neighbour pulls or pushes v along their edge to the size (springs of rest length h).
    const Point3 old = out.points[v];
    Point3 aim(0, 0, 0);
    bool coincident = false;
    for (int u : nb) {
      const Point3 d = old - out.points[u];
      const double l = d.Norm();
      coincident |= !(l > 0);
      if (l > 0) aim += out.points[u] + d * (h / l);
    }
    if (coincident) continue;
    aim /= double(nb.size());
    const int patch = out.face_patch[ring[begin[v]]];
    const double before = star_min_angle(out.points, out.faces, rings, int(v));
    const Point3 normal = s.face_normal[out.host[v]];
    for (double t : {1.0, 0.5, 0.25}) {
      const Point3 want = old + (aim - old) * t;
      const Projection pr = locator.locate(want, patch, normal, out.host[v], (want - old).Norm() * 2 + locator.rounding_length());
      if (pr.face < 0) continue;
      const auto after_fit = misfit(pr.point);
      if (after_fit >= before_fit) continue;
      out.points[v] = pr.point;
      if (star_folded(out.points, out.faces, rings, int(v), s.face_normal[pr.face]) ||
          star_min_angle(out.points, out.faces, rings, int(v)) < std::min(before, floor)) {
        out.points[v] = old;
        continue;
      }
      out.host[v] = pr.face;
      ++moves;
      break;
    }
  }
  return moves;
}

int collapse_short_edges(OutputMesh& out, const std::unordered_set<std::uint64_t>& fixed,
                         const SurfaceLocator& locator, const SizeField& size, const std::vector<char>& movable,
                         double floor) {
  return EdgeLengthMoves(out, fixed, locator, size, movable, floor).collapse_short();
}

int split_long_edges(OutputMesh& out, const std::unordered_set<std::uint64_t>& fixed, const SurfaceLocator& locator,
                     const SizeField& size, std::vector<char>& movable, double floor) {
  const std::vector<char> before(movable);
  return EdgeLengthMoves(out, fixed, locator, size, before, floor).split_long(movable);
}

}  // namespace mr::remesh
