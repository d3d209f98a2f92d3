#include "remesh/defect_reduction.h"

#include "remesh/side_faces.h"
#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <array>
#include <unordered_map>

namespace mr::remesh {

namespace {

// Rounds of projected Laplacian smoothing a tried sequence gets before it is judged: one round
// leaves the new 6-valent points visibly off-centre, three settle them.
constexpr int kSmoothRounds = 3;

// A kept sequence may lower the mean smallest angle of the faces it judged by at most this
// (radians): none at all kept part's valence-6 share at 0.946, no bound let fandisk's mean
// smallest angle fall from 56.86 to 56.57 degrees.
constexpr double kMeanAngleSlack = 0.3 * 3.14159265358979323846 / 180.0;

// Longest swap sequence tried (part at 1%: valence-6 share 0.944 with 2, 0.947 with 4, 0.948
// with 5 at twice the search time).
constexpr int kMaxSwaps = 4;

// Sequences judged (smoothed and measured) around one point before its search gives up: the
// judging is the costly part, and a point whose first tries all fail rarely succeeds later.
constexpr int kMaxTries = 4;

// Swaps only pairs whose normals agree at least this well (cosine), as the post-pass's swaps.
constexpr double kFlatPair = 0.9;

// Sequences are judged only where every face of their patch around them is this close (cosine)
// to their mean normal (bunny at 1%: distance to the input 0.0031 -> 0.0026 of the diagonal,
// valence-6 share 0.885 -> 0.847; part unchanged).
constexpr double kFlatRegion = 0.9;

// A swappable pair: face f = (x, y, c) and face g = (y, x, d) become (x, d, c) and (d, y, c).
struct Quad {
  int f, g, x, y, c, d;
  int energy_change;  ///< of the squared valence deviation
};

struct FaceChange {
  int face;
  std::array<int, 3> before;
};

class DefectReducer {
public:
  DefectReducer(OutputMesh& out, const std::unordered_set<std::uint64_t>& fixed, const SurfaceLocator& locator,
                const std::vector<char>& movable, double floor)
      : out_(out), fixed_(fixed), locator_(locator), movable_(movable), floor_(floor),
        sides_(out.faces), vertex_faces_(out.points.size()), valence_(out.points.size(), 0),
        ideal_(out.points.size(), 6) {
    for (size_t f = 0; f < out.faces.size(); ++f)
      for (int v : out.faces[f]) vertex_faces_[v].push_back(int(f));
    // Valence = distinct edges; a point on an open border wants 4 (as the valence swaps do).
    for (const auto& F : out.faces)
      for (int z = 0; z < 3; ++z) {
        const int a = F[z], b = F[(z + 1) % 3];
        const bool border = sides_.face_of(b, a) < 0;
        if (border || a < b) valence_[a]++, valence_[b]++;
        if (border) ideal_[a] = ideal_[b] = 4;
      }
  }

  DefectReductionResult run(const std::vector<char>& region) {
    DefectReductionResult r;
    for (size_t v = 0; v < out_.points.size(); ++v) {
      if (!region[v] || deviation(int(v), 0) == 0) continue;
      const size_t swaps = try_around(int(v), r);
      if (swaps > 0) {
        r.sequences++;
        r.swaps += int(swaps);
      }
    }
    return r;
  }

private:
  int deviation(int v, int change) const {
    if (out_.kind[v] == PointKind::Corner) return 0;
    const int e = valence_[v] + change - ideal_[v];
    return e * e;
  }

  int energy_change(const Quad& q) const {
    return deviation(q.x, -1) + deviation(q.y, -1) + deviation(q.c, 1) + deviation(q.d, 1) -
           deviation(q.x, 0) - deviation(q.y, 0) - deviation(q.c, 0) - deviation(q.d, 0);
  }

  // Side z of face f as a swap, when that swap keeps the mesh manifold.
  bool quad_of(int f, int z, Quad& q) const {
    FacePair p;
    if (!sides_.swappable_pair(out_, f, z, p)) return false;
    q.f = p.f, q.g = p.g, q.x = p.x, q.y = p.y, q.c = p.c, q.d = p.d;
    if (fixed_.count(OutputMesh::edge_key(q.x, q.y)) || out_.face_patch[q.g] != out_.face_patch[f]) return false;
    if (valence_[q.x] <= 3 || valence_[q.y] <= 3) return false;
    q.energy_change = energy_change(q);
    return true;
  }

  // Does the swap keep the surface's shape: a nearly flat pair, new faces not folded over it?
  bool keeps_shape(const Quad& q) const {
    const auto& P = out_.points;
    const Point3 nf = unit_normal(P[q.x], P[q.y], P[q.c]), ng = unit_normal(P[q.y], P[q.x], P[q.d]);
    if (nf * ng < kFlatPair) return false;
    const Point3 n = (nf + ng).Normalize();
    return unit_normal(P[q.x], P[q.d], P[q.c]) * n > 0.5 && unit_normal(P[q.d], P[q.y], P[q.c]) * n > 0.5;
  }

  void set_face(int f, const std::array<int, 3>& t) {
    for (int v : out_.faces[f]) {
      auto& list = vertex_faces_[v];
      list.erase(std::find(list.begin(), list.end(), f));
    }
    sides_.set_face(out_, f, t);
    for (int v : t) vertex_faces_[v].push_back(f);
  }

  void apply(const Quad& q) {
    log_.push_back({q.f, out_.faces[q.f]});
    log_.push_back({q.g, out_.faces[q.g]});
    set_face(q.f, {q.x, q.d, q.c});
    set_face(q.g, {q.d, q.y, q.c});
    valence_[q.x]--, valence_[q.y]--, valence_[q.c]++, valence_[q.d]++;
  }

  void undo_to(size_t mark) {
    while (log_.size() > mark) {
      // Two entries per swap; the valences come back with the faces.
      const FaceChange g = log_.back();
      log_.pop_back();
      const FaceChange f = log_.back();
      log_.pop_back();
      const auto A = out_.faces[f.face];  // (x, d, c)
      const auto B = out_.faces[g.face];  // (d, y, c)
      valence_[A[0]]++, valence_[B[1]]++, valence_[A[2]]--, valence_[A[1]]--;
      set_face(f.face, f.before);
      set_face(g.face, g.before);
    }
  }

  // The swaps of the edges of the faces around `points` (`rings` 1) or around their neighbours
  // too (2) that do not raise the deviation, each edge once.
  std::vector<Quad> candidates_near(const std::vector<int>& points, int rings) const {
    std::vector<int> faces;
    for (int p : points)
      for (int f : vertex_faces_[p]) {
        if (rings == 1) faces.push_back(f);
        else for (int u : out_.faces[f]) faces.insert(faces.end(), vertex_faces_[u].begin(), vertex_faces_[u].end());
      }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    std::vector<Quad> quads;
    Quad q{};
    for (int f : faces)
      for (int z = 0; z < 3; ++z)
        if (out_.faces[f][z] < out_.faces[f][(z + 1) % 3] && quad_of(f, z, q) && q.energy_change <= 0 &&
            keeps_shape(q))
          quads.push_back(q);
    return quads;
  }

  // Swap sequences around v that lower the deviation, the first kept wins; returns its number of
  // swaps (0: none kept).
  size_t try_around(int v, DefectReductionResult& r) {
    tries_left_ = kMaxTries;
    return extend({v}, 2, kMaxSwaps, log_.size(), r);
  }

  // Depth first: a swap near `points` that lowers the deviation, else one that keeps it (a 5-7
  // pair gliding one step) followed by a shorter sequence near its new edge.
  size_t extend(const std::vector<int>& points, int rings, int swaps_left, size_t mark, DefectReductionResult& r) {
    const std::vector<Quad> quads = candidates_near(points, rings);
    for (const Quad& q : quads) {
      if (q.energy_change >= 0) continue;
      if (tries_left_-- <= 0) return 0;
      apply(q);
      if (smoothed_and_accepted(mark, r)) return 1;
      undo_to(log_.size() - 2);
    }
    if (swaps_left <= 1 || tries_left_ <= 0) return 0;
    for (const Quad& q : quads) {
      // (Swapping back the edge the last swap made only returns to where the sequence was.)
      if (q.energy_change != 0 || (log_.size() > mark && std::count(points.begin(), points.end(), q.x) &&
                                    std::count(points.begin(), points.end(), q.y)))
        continue;
      apply(q);
      if (const size_t more = extend({q.c, q.d}, 1, swaps_left - 1, mark, r)) return more + 1;
      undo_to(log_.size() - 2);
      if (tries_left_ <= 0) return 0;
    }
    return 0;
  }

  Point3 face_normal(int f, const std::unordered_map<int, std::array<int, 3>>& original) const {
    const auto it = original.find(f);
    const auto& t = it != original.end() ? it->second : out_.faces[f];
    return unit_normal(out_.points[t[0]], out_.points[t[1]], out_.points[t[2]]);
  }

  double face_min_angle(const std::array<int, 3>& t) const {
    return min_angle(out_.points[t[0]], out_.points[t[1]], out_.points[t[2]]);
  }

  // The surface normal a face of the output should agree with: the host face of one of its
  // points in its own patch.
  bool folded(int f) const {
    const auto& t = out_.faces[f];
    const Surface& s = locator_.surface();
    for (int v : t) {
      const int h = out_.host[v];
      if (h < 0 || s.group[h] != out_.face_patch[f]) continue;
      return unit_normal(out_.points[t[0]], out_.points[t[1]], out_.points[t[2]]) * s.face_normal[h] < 0.5;
    }
    return false;
  }

  // Smooths the free points around the swaps since `mark`, then keeps all when the faces around
  // stay above min(their old smallest angle, floor) and unfolded; else puts the points back (the
  // caller undoes the swaps).
  bool smoothed_and_accepted(size_t mark, DefectReductionResult& r) {
    r.tried++;
    std::vector<int> touched;
    for (size_t k = mark; k < log_.size(); ++k)
      for (int v : out_.faces[log_[k].face]) touched.push_back(v);
    std::vector<int> around(touched);
    for (int v : touched)
      for (int f : vertex_faces_[v]) around.insert(around.end(), out_.faces[f].begin(), out_.faces[f].end());
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    std::vector<int> faces, smooth;
    for (int v : around) {
      faces.insert(faces.end(), vertex_faces_[v].begin(), vertex_faces_[v].end());
      if (out_.kind[v] == PointKind::Free && movable_[v]) smooth.push_back(v);
    }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    // The faces as they were (a swapped face's first logged content) at today's points.
    std::unordered_map<int, std::array<int, 3>> original;
    for (size_t k = mark; k < log_.size(); ++k) original.emplace(log_[k].face, log_[k].before);
    // Only where the surface is nearly flat across the judged faces: on tight bends (the bunny's
    // ears) the smoothing pulls the points together and the faces cut the bend (bunny at 1%:
    // distance to the input 0.0024 -> 0.0031 of the diagonal without this check).
    // (Faces of the swaps' patch only: across a feature line the surface bends by design.)
    const int patch = out_.face_patch[log_[mark].face];
    Point3 mean_normal(0, 0, 0);
    for (int f : faces) if (out_.face_patch[f] == patch) mean_normal += face_normal(f, original);
    mean_normal.Normalize();
    for (int f : faces)
      if (out_.face_patch[f] == patch && face_normal(f, original) * mean_normal < kFlatRegion) return false;
    double before = 1e9, before_sum = 0;
    for (int f : faces) {
      const auto it = original.find(f);
      const auto& t = it != original.end() ? it->second : out_.faces[f];
      const double a = face_min_angle(t);
      before = std::min(before, a);
      before_sum += a;
    }
    std::vector<Point3> old_points;
    std::vector<int> old_hosts;
    for (int v : smooth) old_points.push_back(out_.points[v]), old_hosts.push_back(out_.host[v]);
    const Surface& s = locator_.surface();
    for (int round = 0; round < kSmoothRounds; ++round)
      for (int v : smooth) {
        Point3 centre(0, 0, 0);
        int count = 0;
        for (int f : vertex_faces_[v])
          for (int u : out_.faces[f]) if (u != v) centre += out_.points[u], ++count;
        centre /= double(count);
        const int patch = out_.face_patch[vertex_faces_[v].front()];
        const Point3 normal = out_.host[v] >= 0 ? s.face_normal[out_.host[v]] : Point3(0, 0, 0);
        const Projection pr =
            locator_.locate(centre, patch, normal, out_.host[v], (centre - out_.points[v]).Norm() * 2 + locator_.rounding_length());
        if (pr.face < 0) continue;
        out_.points[v] = pr.point;
        out_.host[v] = pr.face;
      }
    double after = 1e9, after_sum = 0;
    bool fold = false;
    for (int f : faces) {
      const double a = face_min_angle(out_.faces[f]);
      after = std::min(after, a);
      after_sum += a;
      fold = fold || folded(f);
    }
    if (!fold && after >= std::min(before, floor_) && after_sum >= before_sum - kMeanAngleSlack * faces.size()) {
      r.moves += int(smooth.size());
      return true;
    }
    for (size_t k = 0; k < smooth.size(); ++k) out_.points[smooth[k]] = old_points[k], out_.host[smooth[k]] = old_hosts[k];
    return false;
  }

  OutputMesh& out_;
  const std::unordered_set<std::uint64_t>& fixed_;
  const SurfaceLocator& locator_;
  const std::vector<char>& movable_;
  const double floor_;
  SideFaces sides_;
  std::vector<std::vector<int>> vertex_faces_;
  std::vector<int> valence_, ideal_;
  std::vector<FaceChange> log_;
  int tries_left_ = 0;  // sequences the search around the current point may still judge
};

}  // namespace

DefectReductionResult reduce_valence_defects(OutputMesh& out, const std::unordered_set<std::uint64_t>& fixed,
                                             const SurfaceLocator& locator, const std::vector<char>& region,
                                             const std::vector<char>& movable, double floor) {
  return DefectReducer(out, fixed, locator, movable, floor).run(region);
}

}  // namespace mr::remesh
