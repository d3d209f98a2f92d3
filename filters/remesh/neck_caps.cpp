#include "remesh/neck_caps.h"

#include "common/segment_geometry.h"
#include "common/uniform_grid.h"
#include "remesh/output_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace mr::remesh {

namespace {

// Lines closer than this x target make a neck: a row of faces across it with points a target
// apart has angles of about atan(width / target), under 9 degrees at 0.15 x target.
constexpr double kNeck = 0.15;
// Caps never go below kFloor x target; 1.7 x the width gives 30-degree right triangles across
// the neck (the same bounds as thin steps, thin_step_caps.cpp).
constexpr double kFloor = 0.05, kCap = 1.7;
// Between two lines the caller gave, caps go down to this x target: held at kFloor, strips
// under 0.03 x target wide between two intersection circles kept rows of faces of 22-26 degrees
// (the 200-sphere cluster at 1%, 0.002 wide). 0.02 left a face of 7.8 degrees at the end of a
// strip 0.005 x target wide (fuzz_union --models seed 84, 11.7 before); 0.01 gave 13.7 there.
// Lines found by their dihedral angle keep kFloor.
constexpr double kGivenFloor = 0.01;
// Consecutive neck points along a line that make a neck. Measured on fuzz_union --models seeds
// 0-95 at 1% and 0-23 at 2%, union then regrid: with runs of 3, 17 of 120 regrids better and
// none worse; with runs of 2, reach 0.1 x target 26 better and one worse, 0.15 35 better but the
// noisy bunny's strict-mode regrid pinched two points, 0.25 48 better and one worse but
// armadillo.off's edges within [0.7, 1.4] x target fell 95.8 -> 94.0% (scan ridges beside each
// other), for no better angle.
constexpr size_t kMinRun = 3;
// Between two lines the caller gave (the union's intersection lines) the patch is a part of the
// bodies' surface, not scan noise, and is capped from this width on: one row of target-sized
// faces across 0.15-0.3 x target between two intersection circles had 14-26 degrees. Lines
// found by their dihedral angle keep kNeck: armadillo.off's scan ridges beside each other,
// capped from 0.45, kept 93.4% of its edges within [0.7, 1.4] x target instead of 95.7%.
constexpr double kGivenNeck = 0.45;
// Points in a row that make such a wider neck. Runs of 3 there also capped where two lines
// come within the reach for a short stretch near their ends (a wedge whose tip the cut split
// into corners a fraction of the target apart) and made the faces at those tips worse:
// fuzz_union --models seeds 0-95 at 1%, union then regrid, 13 better and 3 worse, with
// relax_wedges 18 better and 5 worse (seed 50 30.04 -> 26.0 degrees); runs of 4 6 and 14 better,
// 1 worse, but the 200-sphere cluster 14.34 -> 12.83; runs of 5 2 and 8 better, none worse, and
// the 200-sphere cluster the same (with relax_wedges 18.90 -> 19.32); seeds 0-23 at 2%, 4 and 2
// better, one worse by 0.02 degrees.
constexpr size_t kMinGivenRun = 5;

}  // namespace

std::vector<char> given_lines(const TriMesh& mesh, const std::vector<features::DiscreteLine>& lines, bool use_selected) {
  std::vector<char> given(lines.size(), 0);
  if (!use_selected) return given;
  std::unordered_set<std::uint64_t> selected;
  for (const auto& f : mesh.face)
    if (!f.IsD())
      for (int z = 0; z < 3; ++z)
        if (f.IsFaceEdgeS(z))
          selected.insert(OutputMesh::edge_key(int(vcg::tri::Index(mesh, f.cV(z))), int(vcg::tri::Index(mesh, f.cV((z + 1) % 3)))));
  if (selected.empty()) return given;
  for (size_t l = 0; l < lines.size(); ++l) {
    const auto& v = lines[l].vertices;
    const size_t n = v.size();
    if (n < 2) continue;
    const size_t segments = lines[l].closed ? n : n - 1;
    bool all = true;
    for (size_t k = 0; k < segments && all; ++k) all = selected.count(OutputMesh::edge_key(v[k], v[(k + 1) % n])) > 0;
    given[l] = all;
  }
  return given;
}

int cap_necks(const Surface& s, const std::vector<features::DiscreteLine>& lines, const std::vector<char>& given,
              double target, std::vector<double>& cap) {
  const double narrow = kNeck * target;
  const double wide = kGivenNeck * target;
  const bool any_given = std::find(given.begin(), given.end(), 1) != given.end();
  const double reach = any_given ? std::max(narrow, wide) : narrow;
  if (!(narrow > 0) || lines.size() < 2) return 0;
  struct Segment {
    int a, b, line;
  };
  std::vector<Segment> segments;
  // Each segment filed in the cells within `reach` of it: a point's own cell lists every
  // segment that close.
  UniformGrid grid(reach);
  for (int l = 0; l < int(lines.size()); ++l) {
    const auto& v = lines[size_t(l)].vertices;
    const size_t n = v.size();
    for (size_t k = 0; k + 1 < n + (lines[size_t(l)].closed ? 1 : 0); ++k) {
      const int a = v[k], b = v[(k + 1) % n];
      grid.insert_segment(int(segments.size()), s.points[size_t(a)], s.points[size_t(b)], reach);
      segments.push_back({a, b, l});
    }
  }
  // Lines that end at one corner meet there: between them lies a wedge (whose narrow end no
  // size fits) or, where they share both ends, twin lines (stage 2 merges those), not a neck.
  auto meet = [&](int l, int m) {
    const auto &a = lines[size_t(l)], &b = lines[size_t(m)];
    if (a.closed || b.closed || a.vertices.empty() || b.vertices.empty()) return false;
    for (int c : {a.vertices.front(), a.vertices.back()})
      if (c == b.vertices.front() || c == b.vertices.back()) return true;
    return false;
  };
  auto is_given = [&](int line) { return size_t(line) < given.size() && given[size_t(line)] != 0; };
  int capped = 0;
  std::vector<double> width;  // per point of the line: distance to the nearest other line, or -1
  std::vector<char> width_given;  // per point: that nearest line and this one were both given
  for (int l = 0; l < int(lines.size()); ++l) {
    const auto& v = lines[size_t(l)].vertices;
    const size_t n = v.size();
    width.assign(n, -1.0);
    width_given.assign(n, 0);
    const bool l_given = is_given(l);
    for (size_t k = 0; k < n; ++k) {
      const Point3& p = s.points[size_t(v[k])];
      double nearest = HUGE_VAL;
      bool nearest_given = false;
      grid.visit(p, 0.0, [&](int q) {
        const Segment& g = segments[size_t(q)];
        if (g.line == l) return;
        const double d = point_segment_distance(p, s.points[size_t(g.a)], s.points[size_t(g.b)]);
        const bool both_given = l_given && is_given(g.line);
        if (d < nearest && d > 0 && d < (both_given ? wide : narrow) && !meet(l, g.line)) {
          nearest = d;
          nearest_given = both_given;
        }
      });
      if (nearest < reach) {
        width[k] = nearest;
        width_given[k] = nearest_given;
      }
    }
    // A neck is a run of at least kMinRun such points along the line: fewer are where two lines
    // touch in passing (the twin ridges of a noisy scan, which caps there pinched the front on
    // the bunny), not a neck.
    const bool closed = lines[size_t(l)].closed;
    std::vector<char> keep(n, 0);
    // Marks runs of at least `min_run` points whose width is under `below`.
    auto mark_runs = [&](double below, size_t min_run) {
      auto in = [&](size_t k) { return width[k] >= 0 && width[k] < below; };
      size_t start = 0;  // a closed line's runs are counted from a point that is none
      if (closed) {
        while (start < n && in(start)) ++start;
        if (start == n) std::fill(keep.begin(), keep.end(), 1);  // close all round
      }
      if (start < n)
        for (size_t i = 0; i < n;) {
          const size_t k = (start + i) % n;
          if (!in(k) || (!closed && start + i >= n)) { ++i; continue; }
          size_t e = i;
          while (e + 1 < n && in((start + e + 1) % n) && (closed || start + e + 1 < n)) ++e;
          if (e - i + 1 >= min_run)
            for (size_t j = i; j <= e; ++j) keep[(start + j) % n] = 1;
          i = e + 1;
        }
    };
    mark_runs(narrow, kMinRun);
    if (reach > narrow) mark_runs(reach, kMinGivenRun);
    for (size_t k = 0; k < n; ++k) {
      if (!keep[k]) continue;
      const double h = std::max(kCap * width[k], (width_given[k] ? kGivenFloor : kFloor) * target);
      double& c = cap[size_t(v[k])];
      c = c > 0 ? std::min(c, h) : h;
      ++capped;
    }
  }
  return capped;
}

}  // namespace mr::remesh
