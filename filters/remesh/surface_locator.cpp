#include "remesh/surface_locator.h"

#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace mr::remesh {

Surface Surface::from_mesh(const TriMesh& mesh, const std::vector<int>& group) {
  std::vector<Point3> pts(mesh.vert.size());
  for (size_t i = 0; i < pts.size(); ++i) pts[i] = mesh.vert[i].cP();
  std::vector<std::array<int, 3>> faces(mesh.face.size());
  for (size_t f = 0; f < faces.size(); ++f)
    for (int z = 0; z < 3; ++z) faces[f][z] = int(vcg::tri::Index(mesh, mesh.face[f].cV(z)));
  return from_arrays(std::move(pts), std::move(faces), group);
}

Surface Surface::from_arrays(std::vector<Point3> points, std::vector<std::array<int, 3>> faces,
                             std::vector<int> group) {
  Surface s;
  s.points = std::move(points);
  s.faces = std::move(faces);
  s.group = group.empty() ? std::vector<int>(s.faces.size(), 0) : std::move(group);
  s.compute_normals_and_neighbours();
  return s;
}

void Surface::compute_normals_and_neighbours() {
  const size_t nf = faces.size();
  face_normal.resize(nf);
  for (size_t f = 0; f < nf; ++f)
    face_normal[f] = unit_normal(points[faces[f][0]], points[faces[f][1]], points[faces[f][2]]);
  // Sides sorted by (min vertex, max vertex): a pair of sides is a manifold edge.
  struct SideKey { int a, b, face, side; };
  std::vector<SideKey> sides;
  sides.reserve(3 * nf);
  for (size_t f = 0; f < nf; ++f)
    for (int z = 0; z < 3; ++z) {
      int a = faces[f][z], b = faces[f][(z + 1) % 3];
      sides.push_back({std::min(a, b), std::max(a, b), int(f), z});
    }
  std::sort(sides.begin(), sides.end(), [](const SideKey& x, const SideKey& y) {
    return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.face != y.face ? x.face < y.face : x.side < y.side;
  });
  neighbour.assign(nf, {-1, -1, -1});
  for (size_t i = 0; i < sides.size();) {
    size_t j = i;
    while (j < sides.size() && sides[j].a == sides[i].a && sides[j].b == sides[i].b) ++j;
    if (j - i == 2) {
      neighbour[sides[i].face][sides[i].side] = sides[i + 1].face;
      neighbour[sides[i + 1].face][sides[i + 1].side] = sides[i].face;
    }
    i = j;
  }
}

namespace {
constexpr long kMaxGridEntries = 6000000;
}

SurfaceLocator::SurfaceLocator(const Surface& surface, double cell) : surface_(surface) {
  Box3 box;
  for (const auto& p : surface.points) box.Add(p);
  origin_ = box.min;
  const double diag = std::max(box.Diag(), 1e-300);
  rounding_length_ = 1e-12 * diag;
  cell_ = std::max(cell, diag * 1e-4);
  // Enlarge cells until the bounding-box cell count of all faces is affordable.
  for (int attempt = 0; attempt < 40; ++attempt) {
    double total = 0;
    for (const auto& f : surface.faces) {
      Box3 fb;
      for (int z = 0; z < 3; ++z) fb.Add(surface.points[f[z]]);
      double n = 1;
      for (int d = 0; d < 3; ++d) n *= std::floor((fb.max[d] - origin_[d]) / cell_) - std::floor((fb.min[d] - origin_[d]) / cell_) + 1;
      total += n;
      if (total > kMaxGridEntries) break;
    }
    if (total <= kMaxGridEntries) break;
    cell_ *= 1.5;
  }
  const double half_diag = cell_ * std::sqrt(3.0) * 0.5;
  for (size_t fi = 0; fi < surface.faces.size(); ++fi) {
    const auto& f = surface.faces[fi];
    const Point3 &a = surface.points[f[0]], &b = surface.points[f[1]], &c = surface.points[f[2]];
    Box3 fb;
    fb.Add(a); fb.Add(b); fb.Add(c);
    auto lo = cell_of(fb.min), hi = cell_of(fb.max);
    const bool single = lo == hi;
    for (long i = lo[0]; i <= hi[0]; ++i)
      for (long j = lo[1]; j <= hi[1]; ++j)
        for (long k = lo[2]; k <= hi[2]; ++k) {
          if (!single) {  // keep only cells the triangle comes near
            Point3 centre = origin_ + Point3((i + 0.5) * cell_, (j + 0.5) * cell_, (k + 0.5) * cell_);
            std::array<double, 3> bary;
            if ((closest_point_on_triangle(centre, a, b, c, bary) - centre).Norm() > half_diag) continue;
          }
          grid_[key(i, j, k)].push_back(int(fi));
        }
  }
  stamp_.assign(surface.faces.size(), 0);
  face_box_.resize(surface.faces.size());
  for (size_t f = 0; f < surface.faces.size(); ++f) {
    const auto& t = surface.faces[f];
    const Point3 &a = surface.points[t[0]], &b = surface.points[t[1]], &c = surface.points[t[2]];
    for (int axis = 0; axis < 3; ++axis) {
      face_box_[f][size_t(axis)] = std::min({a[axis], b[axis], c[axis]});
      face_box_[f][size_t(3 + axis)] = std::max({a[axis], b[axis], c[axis]});
    }
  }
  double area = 0;
  for (size_t f = 0; f < surface.faces.size(); ++f) {
    const auto& t = surface.faces[f];
    area += 0.5 * ((surface.points[t[1]] - surface.points[t[0]]) ^ (surface.points[t[2]] - surface.points[t[0]])).Norm();
  }
  mean_face_area_ = surface.faces.empty() ? 0 : area / double(surface.faces.size());
}

SurfaceLocator::Key SurfaceLocator::key(long i, long j, long k) const {
  return (Key(i & 0x1FFFFF) << 42) | (Key(j & 0x1FFFFF) << 21) | Key(k & 0x1FFFFF);
}

std::array<long, 3> SurfaceLocator::cell_of(const Point3& p) const {
  return {long(std::floor((p[0] - origin_[0]) / cell_)), long(std::floor((p[1] - origin_[1]) / cell_)),
          long(std::floor((p[2] - origin_[2]) / cell_))};
}

bool SurfaceLocator::accept(int f, int group, const Point3& normal) const {
  if (group >= 0 && surface_.group[f] != group) return false;
  if (normal.SquaredNorm() > 0 && surface_.face_normal[f] * normal <= 0.5 * normal.Norm()) return false;
  return true;
}

void SurfaceLocator::faces_near(const Point3& p, double radius, std::vector<int>& out) const {
  out.clear();
  if (++stamp_value_ == std::numeric_limits<int>::max()) { std::fill(stamp_.begin(), stamp_.end(), 0); stamp_value_ = 1; }
  const Point3 box_lo = p - Point3(radius, radius, radius), box_hi = p + Point3(radius, radius, radius);
  // A cell holds hundreds of faces when the input is much finer than the elements, and most
  // queries (host of a side, normals at a line point) have a tiny radius: faces whose bounding box
  // misses the query box are left out before the sort, as no point of them is within reach.
  auto box_misses = [&](int f) {
    const auto& fb = face_box_[size_t(f)];
    for (int axis = 0; axis < 3; ++axis)
      if (fb[3 + axis] < box_lo[axis] || fb[axis] > box_hi[axis]) return true;
    return false;
  };
  auto lo = cell_of(box_lo), hi = cell_of(box_hi);
  for (long i = lo[0]; i <= hi[0]; ++i)
    for (long j = lo[1]; j <= hi[1]; ++j)
      for (long k = lo[2]; k <= hi[2]; ++k) {
        auto it = grid_.find(key(i, j, k));
        if (it == grid_.end()) continue;
        for (int f : it->second)
          if (stamp_[f] != stamp_value_) {
            stamp_[f] = stamp_value_;
            if (!box_misses(f)) out.push_back(f);
          }
      }
  std::sort(out.begin(), out.end());
}

// Keeps face f in `best` if p is closer to it; ties (a point on a shared side or corner) go to
// the face whose normal agrees best. Returns the distance from p to f.
double SurfaceLocator::consider_face(int f, const Point3& p, const Point3& normal, Projection& best) const {
  const Surface& s = surface_;
  std::array<double, 3> bary;
  const auto& t = s.faces[f];
  const Point3 q = closest_point_on_triangle(p, s.points[t[0]], s.points[t[1]], s.points[t[2]], bary);
  const double d = (q - p).Norm();
  const double tie = rounding_length_ + 1e-12 * d;
  const bool better = d < best.distance - tie ||
                      (d <= best.distance + tie && best.face >= 0 && normal.SquaredNorm() > 0 &&
                       s.face_normal[f] * normal > s.face_normal[best.face] * normal);
  if (better) { best.face = f; best.point = q; best.bary = bary; best.distance = d; }
  return d;
}

Projection SurfaceLocator::locate(const Point3& p, int group, const Point3& normal, int start, double radius,
                                  SearchStep* step) const {
  Projection best = locate_within(p, group, normal, start, radius, step);
  if (best.face >= 0) return best;
  const Surface& s = surface_;
  best.distance = std::numeric_limits<double>::max();
  auto consider = [&](int f) { consider_face(f, p, normal, best); };
  // 3. Brute force over the allowed faces; without an agreeing normal, any face of the group.
  for (int f = 0; f < int(s.faces.size()); ++f)
    if (accept(f, group, normal)) consider(f);
  if (best.face < 0)
    for (int f = 0; f < int(s.faces.size()); ++f)
      if (group < 0 || s.group[f] == group) consider(f);
  if (step) *step = best.face >= 0 ? SearchStep::BruteForce : SearchStep::None;
  return best;
}

Projection SurfaceLocator::locate_growing(const Point3& p, int group, int start, double first_radius,
                                          double reach) const {
  for (double r = first_radius; r > 0 && r < reach; r *= 4) {
    const Projection pr = locate_within(p, group, Point3(0, 0, 0), start, r);
    if (pr.face >= 0) return pr;
  }
  return locate_within(p, group, Point3(0, 0, 0), start, reach);
}

Projection SurfaceLocator::locate_within(const Point3& p, int group, const Point3& normal, int start, double radius,
                                         SearchStep* step) const {
  const Surface& s = surface_;
  Projection best;
  best.distance = std::numeric_limits<double>::max();
  auto consider = [&](int f) { return consider_face(f, p, normal, best); };

  // 1. Walk: breadth-first over neighbours of the start face, only through faces within `radius`.
  if (start >= 0 && start < int(s.faces.size())) {
    if (++stamp_value_ == std::numeric_limits<int>::max()) { std::fill(stamp_.begin(), stamp_.end(), 0); stamp_value_ = 1; }
    std::vector<int> queue{start};
    stamp_[start] = stamp_value_;
    // Enough visits to cover the faces within `radius` (a disc of pi r^2 on a flat surface): an
    // input much finer than the elements (832k faces at 1% elements) otherwise sends every
    // search on to the grid, whose cells then hold hundreds of faces each.
    const double disc = mean_face_area_ > 0 ? 3.2 * radius * radius / mean_face_area_ : 0;
    const size_t max_visits = size_t(std::clamp(disc, 256.0, 65536.0));
    for (size_t head = 0; head < queue.size() && head < max_visits; ++head) {
      const int f = queue[head];
      double d = std::numeric_limits<double>::max();
      if (accept(f, group, normal)) d = consider(f);
      else {
        std::array<double, 3> bary;
        const auto& t = s.faces[f];
        d = (closest_point_on_triangle(p, s.points[t[0]], s.points[t[1]], s.points[t[2]], bary) - p).Norm();
      }
      if (d > radius && f != start) continue;
      // Walk on only near the closest point so far: a face farther than its own size beyond it
      // cannot lead closer on a surface that does not fold back within one face, and without
      // this bound the walk would flood every face within `radius` (many when elements are
      // much larger than the input faces) and end inconclusive.
      const auto& t = s.faces[f];
      const double size = std::max({(s.points[t[1]] - s.points[t[0]]).Norm(), (s.points[t[2]] - s.points[t[1]]).Norm(),
                                    (s.points[t[0]] - s.points[t[2]]).Norm()});
      if (best.face >= 0 && d > best.distance + 2.0 * size && f != start) continue;
      for (int z = 0; z < 3; ++z) {
        int g = s.neighbour[f][z];
        if (g >= 0 && stamp_[g] != stamp_value_ && (group < 0 || s.group[g] == group)) {
          stamp_[g] = stamp_value_;
          queue.push_back(g);
        }
      }
    }
    // The walk is conclusive when it found a face and did not run out of budget.
    if (best.face >= 0 && queue.size() < max_visits && best.distance <= radius) {
      if (step) *step = SearchStep::Walk;
      return best;
    }
  }
  // 2. Grid: every face stored in the cells around p.
  std::vector<int> near;
  faces_near(p, radius, near);
  for (int f : near)
    if (accept(f, group, normal)) consider(f);
  if (best.face >= 0 && best.distance <= radius) {
    if (step) *step = SearchStep::Grid;
    return best;
  }
  if (step) *step = SearchStep::None;
  return Projection{};
}

}  // namespace mr::remesh
