#include "remesh/line_sliding.h"

#include "remesh/face_rings.h"
#include "remesh/line_arcs.h"
#include "remesh/star_shape.h"
#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace mr::remesh {

namespace {

// Tried places between the two neighbours, as fractions of the arc between them: not closer to
// a neighbour than a sixth of it, so no line segment becomes much shorter than its neighbour.
constexpr double kFractions[] = {1.0 / 6, 2.0 / 6, 3.0 / 6, 4.0 / 6, 5.0 / 6};
// Where none of those is better, the places halfway between them (a point beside a short
// line between two corners often needs one of these to reach the goal).
constexpr double kFinerFractions[] = {1.5 / 6, 2.5 / 6, 3.5 / 6, 4.5 / 6};
// Where none of those is better, steps of this fraction of the arc on both sides of the point's
// own place, up to kNearSteps of them: the place that reaches the goal can lie a few percent of
// the arc from where the point is, between the places above (rabbit.obj at 2%: a first segment of
// 0.064 beside a 98-degree corner, whose face reaches 30 degrees at 0.058 to 0.061).
constexpr double kNearStep = 1.0 / 48;
constexpr int kNearSteps = 4;
// A face around the moved point may turn by at most 60 degrees (it must not fold over).
constexpr double kMinNormalAgreement = 0.5;
// Angles closer than this (radians) are taken as equal: a wedge tip's angle changes by rounding
// when the point beside it slides along a straight line.
constexpr double kAngleTie = 1e-9;
// A slide between the bounds that falls short of the goal must gain at least this (radians).
constexpr double kMinGain = 0.5 * 3.14159265358979323846 / 180.0;

/// Unit normals of the faces around point x, in ring order.
std::vector<Point3> ring_normals(const OutputMesh& out, const FaceRings& rings, int x) {
  std::vector<Point3> n;
  for (int k = rings.begin[x]; k < rings.begin[x + 1]; ++k) {
    const auto& f = out.faces[rings.item[k]];
    n.push_back(unit_normal(out.points[f[0]], out.points[f[1]], out.points[f[2]]));
  }
  return n;
}

/// Some face around x turned from its normal in `before` by more than kMinNormalAgreement allows.
bool ring_folded(const OutputMesh& out, const FaceRings& rings, int x, const std::vector<Point3>& before) {
  for (int k = rings.begin[x]; k < rings.begin[x + 1]; ++k) {
    const auto& f = out.faces[rings.item[k]];
    if (unit_normal(out.points[f[0]], out.points[f[1]], out.points[f[2]]) * before[size_t(k - rings.begin[x])] <
        kMinNormalAgreement)
      return true;
  }
  return false;
}

/// Point v (index i of path p), which no slide of its own lifts to the goal, slides together with
/// a slidable point u on a face around it (of another line, or of its own but not next to it): at a
/// corner where three lines leave, a face between two of them is bounded by both first segments,
/// and each point alone cannot move without pushing the other's faces under the goal. Every pair
/// of the places a point tries alone is weighed; the best is kept where the smallest angle off the
/// wedge tips around both points reaches the goal and rises, no tip narrows and no face turns over.
/// With `short_gain` > 0 a pair need only raise the smaller of the two rings' angles off the tips
/// by that much (or to the goal). Returns whether a pair moved (both are then in `moved`).
bool slide_with_partner(OutputMesh& out, std::vector<LinePath>& paths, const std::vector<std::array<int, 2>>& slot,
                        const FaceRings& rings, const std::unordered_set<std::uint64_t>& feature_keys,
                        const std::vector<double>& cumulative_v, int p, int i, const StarAngles& was_v,
                        double goal_rad, std::vector<int>& moved, double short_gain = 0) {
  LinePath& path_v = paths[size_t(p)];
  const int v = path_v.points[size_t(i)];
  auto ring_angles = [&](int x) { return star_angles(out.points, out.faces, rings, x, feature_keys); };
  static const std::vector<double> fractions = [] {  // every place one point tries alone
    std::vector<double> all(std::begin(kFractions), std::end(kFractions));
    all.insert(all.end(), std::begin(kFinerFractions), std::end(kFinerFractions));
    return all;
  }();
  const std::vector<Point3> normals_v = ring_normals(out, rings, v);
  const Point3 old_v = out.points[v];
  const double lo_v = path_v.arc[size_t(i) - 1], hi_v = path_v.arc[size_t(i) + 1];
  std::vector<int> tried;
  for (int k = rings.begin[v]; k < rings.begin[v + 1]; ++k)
    for (int u : out.faces[rings.item[k]]) {
      if (u == v || slot[size_t(u)][0] < 0 || std::find(tried.begin(), tried.end(), u) != tried.end()) continue;
      tried.push_back(u);
      const int q = slot[size_t(u)][0], j = slot[size_t(u)][1];
      if (q == p && std::abs(j - i) < 2) continue;  // next to v on its line: each bounds the other's arc
      LinePath& path_u = paths[size_t(q)];
      const std::vector<double> cumulative_u = cumulative_arc(path_u);
      const StarAngles was_u = ring_angles(u);
      const std::vector<Point3> normals_u = ring_normals(out, rings, u);
      const Point3 old_u = out.points[u];
      const double lo_u = path_u.arc[size_t(j) - 1], hi_u = path_u.arc[size_t(j) + 1];
      const double was = std::min(was_v.off_wedges, was_u.off_wedges);
      double best = short_gain > 0 ? std::min(was + short_gain, goal_rad - kAngleTie)
                                   : std::max(was, goal_rad - kAngleTie);
      double best_sv = -1, best_su = -1;
      ArcPlacement place_v, place_u;
      for (double tv : fractions)
        for (double tu : fractions) {
          const double sv = lo_v + tv * (hi_v - lo_v), su = lo_u + tu * (hi_u - lo_u);
          const ArcPlacement pv = at_arc(path_v, cumulative_v, sv), pu = at_arc(path_u, cumulative_u, su);
          out.points[v] = pv.point;
          out.points[u] = pu.point;
          if (ring_folded(out, rings, v, normals_v) || ring_folded(out, rings, u, normals_u)) continue;
          const StarAngles now_v = ring_angles(v), now_u = ring_angles(u);
          if (now_v.tips < was_v.tips - kAngleTie || now_u.tips < was_u.tips - kAngleTie) continue;
          const double now = std::min(now_v.off_wedges, now_u.off_wedges);
          if (now > best + kAngleTie) {
            best = now;
            best_sv = sv;
            best_su = su;
            place_v = pv;
            place_u = pu;
          }
        }
      out.points[v] = old_v;
      out.points[u] = old_u;
      if (best_sv < 0) continue;
      out.points[v] = place_v.point;
      out.host[v] = path_v.segment_host[size_t(place_v.segment)];
      path_v.arc[size_t(i)] = best_sv;
      out.points[u] = place_u.point;
      out.host[u] = path_u.segment_host[size_t(place_u.segment)];
      path_u.arc[size_t(j)] = best_su;
      moved.push_back(v);
      moved.push_back(u);
      return true;
    }
  return false;
}

}  // namespace

std::vector<int> slide_line_points(OutputMesh& out, std::vector<LinePath>& paths,
                                   const std::vector<std::array<int, 2>>& feature_edges, double worse_than_rad,
                                   double goal_rad, bool short_of_goal) {
  const size_t nv = out.points.size();
  const FaceRings rings(nv, out.faces);
  const std::vector<int>& begin = rings.begin;
  const std::unordered_set<std::uint64_t> feature_keys = OutputMesh::edge_key_set(feature_edges);
  auto ring_angles = [&](int v) { return star_angles(out.points, out.faces, rings, v, feature_keys); };
  std::vector<int> moved;
  const std::vector<std::array<int, 2>> slot = slidable_slots(paths, nv);
  for (size_t p = 0; p < paths.size(); ++p) {
    LinePath& path = paths[p];
    if (path.polyline.size() < 2) continue;
    const std::vector<double> cumulative = cumulative_arc(path);
    for (size_t i = 1; i + 1 < path.points.size(); ++i) {
      const int v = path.points[i];
      if (!path.slidable[i] || begin[v] == begin[v + 1]) continue;
      const StarAngles was = ring_angles(v);
      if (was.smallest() >= std::max(worse_than_rad, goal_rad)) continue;
      // Between the two bounds a slide must reach the goal: a small gain there costs the
      // line its even spacing (and its chords their fit) for nothing a user can count on.
      const bool must_reach = was.smallest() >= worse_than_rad;
      const std::vector<Point3> old_normal = ring_normals(out, rings, v);
      const Point3 old = out.points[v];
      const double lo = path.arc[i - 1], hi = path.arc[i + 1];
      // The smallest angle decides, and where it stays at a wedge tip (between two straight
      // lines no slide changes it) the smallest off the tips, as long as no tip narrows.
      double best = was.smallest(), best_off = was.off_wedges, best_arc = -1;
      ArcPlacement best_place;
      // Between the bounds, the largest gain short of the goal (at least kMinGain): taken only
      // where neither a slide of its own nor one in a pair reaches the goal.
      double gain = was.smallest() + kMinGain, gain_arc = -1;
      ArcPlacement gain_place;
      auto weigh = [&](double t, bool small_step = false) {
        const double s = lo + t * (hi - lo);
        const ArcPlacement place = at_arc(path, cumulative, s);
        out.points[v] = place.point;
        if (ring_folded(out, rings, v, old_normal)) return;
        const StarAngles now = ring_angles(v);
        // A small step's gain at a wedge tip (a tip at a curved line widens a little as the point
        // slides) may not cost the faces off the tips more than down to the goal.
        if (small_step && now.off_wedges < std::min(was.off_wedges, goal_rad) - kAngleTie) return;
        const double off = now.tips >= was.tips - kAngleTie ? now.off_wedges : -1.0;
        const bool better = now.smallest() > best + kAngleTie ||
                            (std::abs(now.smallest() - best) <= kAngleTie && off > best_off + kAngleTie);
        if (better && (!must_reach || now.smallest() >= goal_rad)) {
          best = now.smallest();
          best_off = off;
          best_arc = s;
          best_place = place;
        } else if (must_reach && short_of_goal && now.smallest() > gain) {
          gain = now.smallest();
          gain_arc = s;
          gain_place = place;
        }
      };
      for (double t : kFractions) weigh(t);
      if (best_arc < 0)
        for (double t : kFinerFractions) weigh(t);
      if (best_arc < 0 && hi > lo) {
        const double here = (path.arc[i] - lo) / (hi - lo);
        for (int k = 1; k <= kNearSteps; ++k)
          for (double t : {here - k * kNearStep, here + k * kNearStep})
            if (t >= kFractions[0] && t <= kFractions[4]) weigh(t, true);
      }
      out.points[v] = old;
      // A gain of its own short of the goal comes before any pair: the plain sweeps before
      // these already found no pair that reaches the goal from where the points were.
      if (best_arc < 0 && gain_arc >= 0) {
        best_arc = gain_arc;
        best_place = gain_place;
      }
      // (Only from between the bounds: below them the pair rarely reaches the goal, and on a
      // noisy scan's ridges every point would weigh its 81 pairs with each partner.) Asked for
      // gains short of the goal, one weighing of the pairs takes either.
      if (best_arc < 0 && was.off_wedges >= worse_than_rad && was.off_wedges < goal_rad &&
          slide_with_partner(out, paths, slot, rings, feature_keys, cumulative, int(p), int(i), was, goal_rad, moved,
                             short_of_goal && must_reach ? kMinGain : 0.0))
        continue;
      if (best_arc < 0) continue;
      out.points[v] = best_place.point;
      out.host[v] = path.segment_host[best_place.segment];
      path.arc[i] = best_arc;
      moved.push_back(v);
    }
  }
  return moved;
}

}  // namespace mr::remesh
