#include "remesh/angle_smoothing.h"

#include "remesh/face_rings.h"
#include "remesh/star_shape.h"
#include "remesh/triangle_geometry.h"

#include <array>

namespace mr::remesh {

namespace {

// The search starts with steps of a quarter of the ring's mean edge and stops below a
// hundredth of it; a place farther than half an edge from the start is not taken (the point
// would leave its ring's middle, and its faces their shapes for the others).
constexpr double kFirstStep = 0.25, kLastStep = 0.01, kReach = 0.5;
constexpr int kMaxSteps = 60;
constexpr double kDiagonal = 0.70710678118654752440;  // 1 / sqrt(2)

}  // namespace

std::vector<int> raise_pinched_free_points(OutputMesh& out, const SurfaceLocator& locator,
                                           const std::vector<char>& movable, double goal_rad) {
  const size_t nv = out.points.size();
  const FaceRings rings(nv, out.faces);
  const Surface& s = locator.surface();
  std::vector<int> moved;
  for (size_t i = 0; i < nv; ++i) {
    const int v = int(i);
    if (i >= movable.size() || out.kind[v] != PointKind::Free || !movable[v] || rings.begin[v] == rings.begin[v + 1] ||
        out.host[v] < 0)
      continue;
    const double before = star_min_angle(out.points, out.faces, rings, v);
    if (before >= goal_rad) continue;
    const int patch = out.face_patch[rings.item[rings.begin[v]]];
    const auto& first_face = out.faces[rings.item[rings.begin[v]]];
    const int neighbour = first_face[0] != v ? first_face[0] : first_face[1];  // fixes the frame's e1
    const double edge = mean_ring_edge(out.points, out.faces, rings, v);
    const Point3 start = out.points[v];
    Point3 at = start;
    int host = out.host[v];
    double best = before;
    double step = kFirstStep * edge;
    for (int n = 0; n < kMaxSteps && step >= kLastStep * edge; ++n) {
      const Point3 normal = s.face_normal[host];
      const TangentFrame f(at, out.points[neighbour] - at, normal);
      const std::array<Point3, 8> directions{f.e1, -f.e1, f.e2, -f.e2, (f.e1 + f.e2) * kDiagonal,
                                             (f.e1 - f.e2) * kDiagonal, (f.e2 - f.e1) * kDiagonal,
                                             (f.e1 + f.e2) * -kDiagonal};
      Point3 next = at;
      int next_host = host;
      double next_best = best;
      for (const Point3& d : directions) {
        const Projection pr =
            locator.locate(at + d * step, patch, normal, host, 2 * step + locator.rounding_length());
        if (pr.face < 0 || (pr.point - start).Norm() > kReach * edge) continue;
        out.points[v] = pr.point;
        if (star_folded(out.points, out.faces, rings, v, s.face_normal[pr.face])) continue;
        const double a = star_min_angle(out.points, out.faces, rings, v);
        if (a > next_best + 1e-12) { next_best = a; next = pr.point; next_host = pr.face; }
      }
      if (next_best > best) { best = next_best; at = next; host = next_host; }
      else step *= 0.5;
    }
    if (best > before + 1e-9) {
      out.points[v] = at;
      out.host[v] = host;
      moved.push_back(v);
    } else {
      out.points[v] = start;
    }
  }
  return moved;
}

}  // namespace mr::remesh
