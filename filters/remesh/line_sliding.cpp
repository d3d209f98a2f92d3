#include "remesh/line_sliding.h"

#include "remesh/face_rings.h"
#include "remesh/star_shape.h"
#include "remesh/triangle_geometry.h"

#include <algorithm>
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
// A face around the moved point may turn by at most 60 degrees (it must not fold over).
constexpr double kMinNormalAgreement = 0.5;
// Angles closer than this (radians) are taken as equal: a wedge tip's angle changes by rounding
// when the point beside it slides along a straight line.
constexpr double kAngleTie = 1e-9;

struct Placement {
  Point3 point;
  int segment = 0;
};

Placement at_arc(const LinePath& path, const std::vector<double>& cumulative, double s) {
  const size_t segs = path.polyline.size() - 1;
  size_t seg = std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin();
  seg = std::clamp<size_t>(seg, 1, segs) - 1;
  const double len = cumulative[seg + 1] - cumulative[seg];
  const double u = len > 0 ? std::clamp((s - cumulative[seg]) / len, 0.0, 1.0) : 0.0;
  return {path.polyline[seg] * (1 - u) + path.polyline[seg + 1] * u, int(seg)};
}

}  // namespace

std::vector<int> slide_line_points(OutputMesh& out, std::vector<LinePath>& paths,
                                   const std::vector<std::array<int, 2>>& feature_edges, double worse_than_rad,
                                   double goal_rad) {
  const size_t nv = out.points.size();
  const FaceRings rings(nv, out.faces);
  const std::vector<int>&begin = rings.begin, &ring = rings.item;
  const std::unordered_set<std::uint64_t> feature_keys = OutputMesh::edge_key_set(feature_edges);
  auto ring_angles = [&](int v) { return star_angles(out.points, out.faces, rings, v, feature_keys); };
  std::vector<int> moved;
  std::vector<Point3> old_normal;
  for (LinePath& path : paths) {
    if (path.polyline.size() < 2) continue;
    std::vector<double> cumulative(path.polyline.size(), 0.0);
    for (size_t j = 1; j < path.polyline.size(); ++j)
      cumulative[j] = cumulative[j - 1] + (path.polyline[j] - path.polyline[j - 1]).Norm();
    for (size_t i = 1; i + 1 < path.points.size(); ++i) {
      const int v = path.points[i];
      if (!path.slidable[i] || begin[v] == begin[v + 1]) continue;
      const StarAngles was = ring_angles(v);
      if (was.smallest() >= std::max(worse_than_rad, goal_rad)) continue;
      // Between the two bounds a slide must reach the goal: a small gain there costs the
      // line its even spacing (and its chords their fit) for nothing a user can count on.
      const bool must_reach = was.smallest() >= worse_than_rad;
      old_normal.clear();
      for (int k = begin[v]; k < begin[v + 1]; ++k) {
        const auto& f = out.faces[ring[k]];
        old_normal.push_back(unit_normal(out.points[f[0]], out.points[f[1]], out.points[f[2]]));
      }
      const Point3 old = out.points[v];
      const double lo = path.arc[i - 1], hi = path.arc[i + 1];
      // The smallest angle decides, and where it stays at a wedge tip (between two straight
      // lines no slide changes it) the smallest off the tips, as long as no tip narrows.
      double best = was.smallest(), best_off = was.off_wedges, best_arc = -1;
      Placement best_place;
      auto weigh = [&](double t) {
        const double s = lo + t * (hi - lo);
        const Placement place = at_arc(path, cumulative, s);
        out.points[v] = place.point;
        bool folded = false;
        for (int k = begin[v]; k < begin[v + 1] && !folded; ++k) {
          const auto& f = out.faces[ring[k]];
          folded = unit_normal(out.points[f[0]], out.points[f[1]], out.points[f[2]]) * old_normal[k - begin[v]] <
                   kMinNormalAgreement;
        }
        if (folded) return;
        const StarAngles now = ring_angles(v);
        const double off = now.tips >= was.tips - kAngleTie ? now.off_wedges : -1.0;
        const bool better = now.smallest() > best + kAngleTie ||
                            (std::abs(now.smallest() - best) <= kAngleTie && off > best_off + kAngleTie);
        if (better && (!must_reach || now.smallest() >= goal_rad)) {
          best = now.smallest();
          best_off = off;
          best_arc = s;
          best_place = place;
        }
      };
      for (double t : kFractions) weigh(t);
      if (best_arc < 0)
        for (double t : kFinerFractions) weigh(t);
      out.points[v] = old;
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
