#include "remesh/joint_polish.h"

#include "remesh/face_rings.h"
#include "remesh/line_arcs.h"
#include "remesh/star_shape.h"
#include "remesh/triangle_geometry.h"
#include "remesh/wedge_tips.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace mr::remesh {

namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;
// The search aims this far beyond the goal: corners just at the goal would leave the next
// search around a neighbouring face no room.
constexpr double kAim = 1.0 * kDegree;
// Steps start at this fraction of a line point's two segments (of a free point's mean ring
// edge) and halve down to kLastFactor of that. The 50-sphere cluster's faces under 30 degrees
// reached it with 200-1000 tries; kMaxTries bounds a search where nothing does.
constexpr double kFirstStep = 0.25, kLastFactor = 1.0 / 64;
constexpr int kMaxTries = 500;
// A free point stays within this fraction of its mean ring edge of where it was (as in
// angle_smoothing.cpp: farther, it would leave its ring's middle).
constexpr double kReach = 0.5;
// Faces further under the goal than this are left alone: they are narrower than any place of
// their points mends (a plate's rim, a wedge of the input), and box.STL's hundreds of them made
// its post-pass take half as long again for nothing.
constexpr double kReachableBelowGoal = 10.0 * kDegree;
// A face may turn by at most 60 degrees from where it was (it must not fold over).
constexpr double kMinNormalAgreement = 0.5;
// Angles closer than this (radians) are taken as equal.
constexpr double kAngleTie = 1e-9;

/// A point the search moves: a line point by its arc along its path (between the middles of
/// its two segments, so that two neighbours moving at once keep their order), a free point by
/// two offsets in its tangent plane, projected onto the input in its patch.
struct Mover {
  int v = -1;
  int path = -1, index = -1;  // line point
  double lo = 0, hi = 0;      // its arc's bounds
  TangentFrame frame{Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 0, 1)};  // free point
  int patch = -1;
  double reach = 0;
  Point3 start;
  int start_host = -1;
};

/// What the search minimises and what it must keep, over the faces of one neighbourhood.
struct FaceScore {
  double penalty = 0;   // sum over corners off the tips of (aim - angle)^2 where under the aim
  double off = 1e9;     // smallest angle off the tips
  double tips = 1e9;    // smallest angle at the tips
};

FaceScore score_face(const std::vector<Point3>& points, const std::array<int, 3>& f,
                     const std::unordered_set<std::uint64_t>& feature_keys, double aim) {
  FaceScore s;
  for (int z = 0; z < 3; ++z) {
    const int a = f[z], b = f[(z + 1) % 3], c = f[(z + 2) % 3];
    const double angle = corner_angle(points[a], points[b], points[c]);
    if (is_wedge_tip(angle, a, b, c, feature_keys)) {
      s.tips = std::min(s.tips, angle);
      continue;
    }
    s.off = std::min(s.off, angle);
    if (angle < aim) s.penalty += (aim - angle) * (aim - angle);
  }
  return s;
}

class NeighbourhoodSearch {
public:
  NeighbourhoodSearch(OutputMesh& out, std::vector<LinePath>& paths, const FaceRings& rings,
                      const std::unordered_set<std::uint64_t>& feature_keys, const SurfaceLocator& locator,
                      std::vector<std::vector<double>>& cumulative, double goal_rad)
      : out_(out), paths_(paths), rings_(rings), keys_(feature_keys), locator_(locator), cumulative_(cumulative),
        goal_(goal_rad), stamp_(out.faces.size(), 0) {}

  /// Searches with `movers` (their start filled in here); true when the result is kept.
  bool run(std::vector<Mover>& movers) {
    movers_ = &movers;
    ++round_;
    faces_.clear();
    for (const Mover& m : movers)
      for (int k = rings_.begin[m.v]; k < rings_.begin[m.v + 1]; ++k) {
        const int f = rings_.item[k];
        if (stamp_[f] != round_) { stamp_[f] = round_; faces_.push_back(f); }
      }
    std::sort(faces_.begin(), faces_.end());
    normal_.resize(faces_.size());
    score_.resize(faces_.size());
    for (size_t n = 0; n < faces_.size(); ++n) {
      const auto& f = out_.faces[faces_[n]];
      normal_[n] = unit_normal(out_.points[f[0]], out_.points[f[1]], out_.points[f[2]]);
      score_[n] = score_face(out_.points, f, keys_, goal_ + kAim);
    }
    const FaceScore start = total();
    std::vector<double> x(2 * movers.size(), 0.0), step(x.size(), 0.0);
    for (size_t m = 0; m < movers.size(); ++m) {
      Mover& mv = movers[m];
      mv.start = out_.points[mv.v];
      mv.start_host = out_.host[mv.v];
      if (mv.path >= 0) {
        x[2 * m] = paths_[size_t(mv.path)].arc[size_t(mv.index)];
        step[2 * m] = kFirstStep * 2 * (mv.hi - mv.lo);
      } else {
        step[2 * m] = step[2 * m + 1] = kFirstStep * 2 * mv.reach;
      }
    }
    FaceScore now = start;
    int tries = 0;
    for (double factor = 1; factor >= kLastFactor && tries < kMaxTries;) {
      bool better = false;
      for (size_t k = 0; k < x.size() && tries < kMaxTries; ++k) {
        if (step[k] == 0) continue;
        for (double sign : {1.0, -1.0}) {
          ++tries;
          const double was = x[k];
          const Mover& mv = movers[k / 2];
          const Point3 was_point = out_.points[mv.v];
          const int was_host = out_.host[mv.v];
          x[k] = was + sign * factor * step[k];
          if (mv.path >= 0) x[k] = std::clamp(x[k], mv.lo, mv.hi);
          if (x[k] != was && place(k / 2, x, factor * step[k])) {
            const FaceScore trial = rescore(movers[k / 2].v);
            if (trial.penalty < now.penalty - 1e-15 && trial.off >= start.off - kAngleTie &&
                trial.tips >= start.tips - kAngleTie && !folded_around(mv.v)) {
              now = trial;
              better = true;
              break;
            }
          }
          x[k] = was;
          out_.points[mv.v] = was_point;
          out_.host[mv.v] = was_host;
          rescore(mv.v);
        }
      }
      if (!better) factor *= 0.5;
    }
    if (now.off >= goal_ && now.off > start.off + kAngleTie) {
      for (size_t m = 0; m < movers.size(); ++m)
        if (movers[m].path >= 0) paths_[size_t(movers[m].path)].arc[size_t(movers[m].index)] = x[2 * m];
      return true;
    }
    for (const Mover& mv : movers) {
      out_.points[mv.v] = mv.start;
      out_.host[mv.v] = mv.start_host;
    }
    return false;
  }

private:
  /// Puts mover m where x says; false where a free point finds no host within its reach.
  bool place(size_t m, const std::vector<double>& x, double step) {
    const Mover& mv = (*movers_)[m];
    if (mv.path >= 0) {
      const LinePath& path = paths_[size_t(mv.path)];
      const ArcPlacement at = at_arc(path, cumulative(mv.path), x[2 * m]);
      out_.points[mv.v] = at.point;
      out_.host[mv.v] = path.segment_host[size_t(at.segment)];
      return true;
    }
    const Point3 target = mv.start + mv.frame.e1 * x[2 * m] + mv.frame.e2 * x[2 * m + 1];
    const Projection pr =
        locator_.locate_within(target, mv.patch, mv.frame.normal, out_.host[mv.v], 2 * step + locator_.rounding_length());
    if (pr.face < 0 || (pr.point - mv.start).Norm() > mv.reach) return false;
    out_.points[mv.v] = pr.point;
    out_.host[mv.v] = pr.face;
    return true;
  }

  const std::vector<double>& cumulative(int p) {
    std::vector<double>& c = cumulative_[size_t(p)];
    if (c.empty()) c = cumulative_arc(paths_[size_t(p)]);
    return c;
  }

  /// Index in faces_ of face f (one of the neighbourhood's).
  size_t slot_of(int f) const { return size_t(std::lower_bound(faces_.begin(), faces_.end(), f) - faces_.begin()); }

  /// Scores again the faces around v; returns the neighbourhood's total.
  FaceScore rescore(int v) {
    for (int k = rings_.begin[v]; k < rings_.begin[v + 1]; ++k) {
      const int f = rings_.item[k];
      score_[slot_of(f)] = score_face(out_.points, out_.faces[f], keys_, goal_ + kAim);
    }
    return total();
  }

  FaceScore total() const {
    FaceScore t;
    for (const FaceScore& s : score_) {
      t.penalty += s.penalty;
      t.off = std::min(t.off, s.off);
      t.tips = std::min(t.tips, s.tips);
    }
    return t;
  }

  /// A face around v (the only point just moved) turned too far from where the search began.
  bool folded_around(int v) const {
    for (int k = rings_.begin[v]; k < rings_.begin[v + 1]; ++k) {
      const auto& f = out_.faces[rings_.item[k]];
      if (unit_normal(out_.points[f[0]], out_.points[f[1]], out_.points[f[2]]) * normal_[slot_of(rings_.item[k])] <
          kMinNormalAgreement)
        return true;
    }
    return false;
  }

  OutputMesh& out_;
  std::vector<LinePath>& paths_;
  const FaceRings& rings_;
  const std::unordered_set<std::uint64_t>& keys_;
  const SurfaceLocator& locator_;
  std::vector<std::vector<double>>& cumulative_;
  const double goal_;
  std::vector<int> stamp_;
  int round_ = 0;
  std::vector<Mover>* movers_ = nullptr;
  std::vector<int> faces_;  // ascending
  std::vector<Point3> normal_;
  std::vector<FaceScore> score_;
};

}  // namespace

std::vector<int> polish_jointly(OutputMesh& out, std::vector<LinePath>& paths,
                                const std::vector<std::array<int, 2>>& feature_edges, const SurfaceLocator& locator,
                                const std::vector<char>& movable, double goal_rad, const std::vector<char>& near) {
  const size_t nv = out.points.size();
  const FaceRings rings(nv, out.faces);
  const std::unordered_set<std::uint64_t> feature_keys = OutputMesh::edge_key_set(feature_edges);
  const std::vector<std::array<int, 2>> slot = slidable_slots(paths, nv);
  const Surface& s = locator.surface();
  std::vector<std::vector<double>> cumulative(paths.size());
  NeighbourhoodSearch search(out, paths, rings, feature_keys, locator, cumulative, goal_rad);
  std::vector<int> moved, seen(nv, -1);
  std::vector<Mover> movers;
  for (int f = 0; f < int(out.faces.size()); ++f) {
    const auto& t = out.faces[f];
    if (!near.empty() && !near[size_t(t[0])] && !near[size_t(t[1])] && !near[size_t(t[2])]) continue;
    const double off = score_face(out.points, t, feature_keys, goal_rad).off;
    if (off >= goal_rad || off < goal_rad - kReachableBelowGoal) continue;
    // The face's corners and the points around them.
    movers.clear();
    auto consider = [&](int v) {
      if (seen[size_t(v)] == f) return;
      seen[size_t(v)] = f;
      Mover m;
      m.v = v;
      if (slot[size_t(v)][0] >= 0) {
        m.path = slot[size_t(v)][0];
        m.index = slot[size_t(v)][1];
        const std::vector<double>& arc = paths[size_t(m.path)].arc;
        const size_t i = size_t(m.index);
        m.lo = 0.5 * (arc[i - 1] + arc[i]);
        m.hi = 0.5 * (arc[i] + arc[i + 1]);
        if (!(m.hi > m.lo)) return;
      } else if (out.kind[size_t(v)] == PointKind::Free && size_t(v) < movable.size() && movable[size_t(v)] &&
                 out.host[size_t(v)] >= 0 && rings.begin[v] < rings.begin[v + 1]) {
        const auto& first = out.faces[rings.item[rings.begin[v]]];
        const int neighbour = first[0] != v ? first[0] : first[1];
        m.frame = TangentFrame(out.points[v], out.points[neighbour] - out.points[v], s.face_normal[out.host[v]]);
        m.patch = out.face_patch[rings.item[rings.begin[v]]];
        m.reach = kReach * mean_ring_edge(out.points, out.faces, rings, v);
        if (!(m.reach > 0)) return;
      } else {
        return;
      }
      movers.push_back(m);
    };
    for (int c : out.faces[f])
      for (int k = rings.begin[c]; k < rings.begin[c + 1]; ++k)
        for (int v : out.faces[rings.item[k]]) consider(v);
    if (movers.empty() || !search.run(movers)) continue;
    for (const Mover& m : movers)
      if (!(out.points[m.v] == m.start)) moved.push_back(m.v);
  }
  return moved;
}

}  // namespace mr::remesh
