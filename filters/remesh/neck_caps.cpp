#include "remesh/neck_caps.h"

#include "common/segment_geometry.h"
#include "common/uniform_grid.h"

#include <algorithm>
#include <cmath>

namespace mr::remesh {

namespace {

// Lines closer than this x target make a neck: a row of faces across it with points a target
// apart has angles of about atan(width / target), under 9 degrees at 0.15 x target.
constexpr double kNeck = 0.15;
// Caps never go below kFloor x target; 1.7 x the width gives 30-degree right triangles across
// the neck (the same bounds as thin steps, thin_step_caps.cpp).
constexpr double kFloor = 0.05, kCap = 1.7;
// Consecutive neck points along a line that make a neck. Measured on fuzz_union --models seeds
// 0-95 at 1% and 0-23 at 2%, union then regrid: with runs of 3, 17 of 120 regrids better and
// none worse; with runs of 2, reach 0.1 x target 26 better and one worse, 0.15 35 better but the
// noisy bunny's strict-mode regrid pinched two points, 0.25 48 better and one worse but
// armadillo.off's edges within [0.7, 1.4] x target fell 95.8 -> 94.0% (scan ridges beside each
// other), for no better angle.
constexpr size_t kMinRun = 3;

}  // namespace

int cap_necks(const Surface& s, const std::vector<features::DiscreteLine>& lines, double target,
              std::vector<double>& cap) {
  const double reach = kNeck * target;
  if (!(reach > 0) || lines.size() < 2) return 0;
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
  int capped = 0;
  std::vector<double> width;  // per point of the line: distance to the nearest other line, or -1
  for (int l = 0; l < int(lines.size()); ++l) {
    const auto& v = lines[size_t(l)].vertices;
    const size_t n = v.size();
    width.assign(n, -1.0);
    for (size_t k = 0; k < n; ++k) {
      const Point3& p = s.points[size_t(v[k])];
      double nearest = reach;
      grid.visit(p, 0.0, [&](int q) {
        const Segment& g = segments[size_t(q)];
        if (g.line == l) return;
        const double d = point_segment_distance(p, s.points[size_t(g.a)], s.points[size_t(g.b)]);
        if (d < nearest && d > 0 && !meet(l, g.line)) nearest = d;
      });
      if (nearest < reach) width[k] = nearest;
    }
    // A neck is a run of at least kMinRun such points along the line: fewer are where two lines
    // touch in passing (the twin ridges of a noisy scan, which caps there pinched the front on
    // the bunny), not a neck.
    const bool closed = lines[size_t(l)].closed;
    std::vector<char> keep(n, 0);
    size_t start = 0;  // a closed line's runs are counted from a point that is none
    if (closed) {
      while (start < n && width[start] >= 0) ++start;
      if (start == n) std::fill(keep.begin(), keep.end(), 1);  // close all round
    }
    if (start < n)
      for (size_t i = 0; i < n;) {
        const size_t k = (start + i) % n;
        if (width[k] < 0 || (!closed && start + i >= n)) { ++i; continue; }
        size_t e = i;
        while (e + 1 < n && width[(start + e + 1) % n] >= 0 && (closed || start + e + 1 < n)) ++e;
        if (e - i + 1 >= kMinRun)
          for (size_t j = i; j <= e; ++j) keep[(start + j) % n] = 1;
        i = e + 1;
      }
    for (size_t k = 0; k < n; ++k) {
      if (!keep[k]) continue;
      const double h = std::max(kCap * width[k], kFloor * target);
      double& c = cap[size_t(v[k])];
      c = c > 0 ? std::min(c, h) : h;
      ++capped;
    }
  }
  return capped;
}

}  // namespace mr::remesh
