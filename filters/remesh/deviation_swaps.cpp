#include "remesh/deviation_swaps.h"

#include "remesh/side_faces.h"
#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace mr::remesh {

namespace {

// Face pairs bent by less than about 10 degrees are left alone.
const double kFlat = std::cos(10.0 * 3.14159265358979323846 / 180.0);

struct PairProbe {
  const OutputMesh& out;
  const SurfaceLocator& locator;
  int patch;
  int start;
  double radius;

  // Distance from the input at p, and the input's normal there (zero if no host face is near).
  double distance(const Point3& p, Point3* normal = nullptr) const {
    const Projection pr = locator.locate_growing(p, patch, start, 0.125 * radius, radius);
    if (pr.face < 0) return radius;
    if (normal) *normal = locator.surface().face_normal[pr.face];
    return pr.distance;
  }

  // How far faces (a,b,c) and (b,a,d) stray from the input: at the middle of the diagonal a-b and
  // at both centroids (the other sides are the same before and after a swap).
  double deviation(int a, int b, int c, int d) const {
    const Point3 &pa = out.points[a], &pb = out.points[b], &pc = out.points[c], &pd = out.points[d];
    return std::max({distance((pa + pb) * 0.5), distance((pa + pb + pc) / 3.0), distance((pa + pb + pd) / 3.0)});
  }

  // Does face (a,b,c) agree with the input's normal under its centroid?
  bool follows_surface(int a, int b, int c) const {
    const Point3 &pa = out.points[a], &pb = out.points[b], &pc = out.points[c];
    Point3 n(0, 0, 0);
    distance((pa + pb + pc) / 3.0, &n);
    return unit_normal(pa, pb, pc) * n > 0.5;
  }
};

}  // namespace

int swap_towards_surface(OutputMesh& out, const std::vector<std::array<int, 2>>& feature_edges,
                         const SurfaceLocator& locator, const SizeField& size, const DeviationSwapParams& params) {
  const std::unordered_set<std::uint64_t> fixed = OutputMesh::edge_key_set(feature_edges);
  const double floor = params.min_angle_deg * 3.14159265358979323846 / 180.0;
  SideFaces sides(out.faces);

  int swaps = 0;
  for (int pass = 0; pass < params.passes; ++pass) {
    int swaps_in_pass = 0;
    for (size_t fi = 0; fi < out.faces.size(); ++fi) {
      for (int z = 0; z < 3; ++z) {
        FacePair p;
        if (!sides.swappable_pair(out, int(fi), z, p)) continue;
        const int x = p.x, y = p.y, c = p.c, d = p.d;
        // Each edge once, from its lower end; never a feature edge, never across patches.
        if (x > y || fixed.count(SideFaces::undirected(x, y)) || out.face_patch[p.g] != out.face_patch[fi]) continue;
        // A nearly flat pair is the same surface with either diagonal.
        const Point3 nf = unit_normal(out.points[x], out.points[y], out.points[c]);
        const Point3 ng = unit_normal(out.points[y], out.points[x], out.points[d]);
        if (nf * ng > kFlat) continue;
        const double h = size.at(out.host[x], {1.0 / 3, 1.0 / 3, 1.0 / 3});
        const PairProbe probe{out, locator, out.face_patch[fi], out.host[x], 2.0 * h};
        const double before = probe.deviation(x, y, c, d);
        if (before <= params.min_deviation * h) continue;
        const double old_min = std::min(min_angle(out.points[x], out.points[y], out.points[c]),
                                        min_angle(out.points[y], out.points[x], out.points[d]));
        const double new_min = std::min(min_angle(out.points[x], out.points[d], out.points[c]),
                                        min_angle(out.points[d], out.points[y], out.points[c]));
        if (new_min < std::min(old_min, floor)) continue;
        const double diagonal = (out.points[c] - out.points[d]).Norm();
        if (diagonal > std::max(params.max_length * h, (out.points[x] - out.points[y]).Norm())) continue;
        if (!probe.follows_surface(x, d, c) || !probe.follows_surface(d, y, c)) continue;
        if (probe.deviation(c, d, x, y) >= params.gain * before) continue;

        sides.swap(out, p);
        ++swaps_in_pass;
      }
    }
    swaps += swaps_in_pass;
    if (swaps_in_pass == 0) break;
  }
  return swaps;
}

}  // namespace mr::remesh
