#include "remesh/advancing_front.h"

#include "remesh/point_grid.h"
#include "remesh/triangle_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <unordered_map>
#include <unordered_set>

namespace mr::remesh {

double front_priority(double side_length, int failures) { return side_length * (1.0 + 2.0 * failures); }

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kFlatEar = 1e-6;  // radians: an ear's smallest angle below this is no triangle
constexpr size_t kMaxLastResortLoop = 16;  // longer loops left by the front stay open (reported)
constexpr double kThinLoop = 0.1;           // ... unless they are thin strips of lines (thin_line_loop)
// Work bound of a front besides its step bound: nearby points looked at by the candidate checks,
// per allowed step. The seven benchmark meshes at 1% need at most 1.6 per allowed step in any
// patch; a front stuck on a damaged input (a fuzzed blade with 150 zero-area faces and folds,
// 1500 sides that never close) looked at 50000 per step and ran for a quarter of an hour.
constexpr double kChecksPerStep = 100.0;
// A side's new sides may be this long (x the local size), or 1.5 x the side itself.
constexpr double kFarCandidate = 3.0;

std::uint64_t directed(int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); }

struct Side {
  int a, b;
  int failures = 0;
  bool alive = true;
  Point3 back_normal{0, 0, 0};  ///< normal of the generated face behind the side (zero for initial sides)
};

class PatchMesher {
public:
  PatchMesher(OutputMesh& out, int patch, const SurfaceLocator& locator, const SizeField& size,
              const FrontParams& params)
      : out_(out), patch_(patch), loc_(locator), size_(size), params_(params),
        grid_(std::max(size.max_size(), 1e-300)), face_grid_(std::max(2 * size.max_size(), 1e-300)) {}

  FrontResult run(std::vector<FrontSide> front);

private:
  struct Local { int host = -1; Point3 normal; int degree = 0; std::vector<int> sides; };
  Local& local(int v);
  void add_side(int a, int b, const Point3& back_normal = Point3(0, 0, 0));
  void remove_side(int s);
  /// Takes out pairs of opposite sides (a->b and b->a): the front is the boundary of the part
  /// still to mesh, and such a pair bounds no area. They are what is left of a dangling line
  /// whose faces on both sides closed over it through a point a hair beside it (box.STL united:
  /// an intersection line ending 0.002 from a plate's corner).
  void drop_slits();
  bool try_side(int s);
  bool valid_triangle(int a, int b, const Point3& q, int q_id, const Point3& q_normal, const TangentFrame& side_frame, double h,
                      double min_angle_rad, const std::vector<int>& near_points) const;
  void add_triangle(int a, int b, int c);
  int side_host(int a, int b, const Projection& at_mid, const Point3& back_normal) const;
  Point3 normal_towards(int v, const Point3& reference) const;
  const std::vector<int>& faces_at(int v) const;
  void seed_triangle();
  double estimated_faces() const;
  bool edge_taken(int x, int y) const;
  bool over_other_patch(int a, int b, int c) const;
  bool covers_meshed_area(const Point3& a, const Point3& b, const Point3& c) const;
  bool within_front_angle(int q, int a, int b, const TangentFrame& side_frame) const;
  bool over_generated_face(const Point3& p, const Point3& normal) const;
  void close_loops(size_t max_sides);
  bool thin_line_loop(const std::vector<int>& loop) const;
  void close_loop(std::vector<int> loop);
  bool fan_from_centre(const std::vector<int>& loop, double must_beat = -1.0);

  OutputMesh& out_;
  int patch_;
  const SurfaceLocator& loc_;
  const SizeField& size_;
  FrontParams params_;
  PointGrid grid_;
  PointGrid face_grid_;  // generated faces of this patch by centroid
  std::unordered_map<int, Local> locals_;
  std::vector<Side> sides_;
  std::unordered_map<std::uint64_t, int> front_;   // directed side -> index in sides_
  std::unordered_set<std::uint64_t> used_;          // directed sides of generated faces
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue_;
  FrontResult result_;
  mutable int last_reason_ = 0;  // why the last candidate was rejected (for debugging)
  mutable long checks_ = 0;      // nearby points looked at by the candidate checks so far
  // Per line or corner point: the faces of this patch it lies on. Asked for every nearby
  // point of every candidate, so a stuck front on a damaged input asks it millions of times.
  mutable std::unordered_map<int, std::vector<int>> faces_at_;
  Point3 current_back_{0, 0, 0};  // back normal of the side being processed
};

PatchMesher::Local& PatchMesher::local(int v) {
  auto it = locals_.find(v);
  if (it != locals_.end()) return it->second;
  Local l;
  const Projection pr = loc_.locate(out_.points[v], patch_, Point3(0, 0, 0), out_.host[v], size_.max_size(), nullptr);
  l.host = pr.face;
  l.normal = pr.face >= 0 ? loc_.surface().face_normal[pr.face] : Point3(0, 0, 0);
  grid_.add(v, out_.points[v]);
  return locals_.emplace(v, std::move(l)).first->second;
}

void PatchMesher::add_side(int a, int b, const Point3& back_normal) {
  const int failures = 0;
  Side s{a, b, failures, true, back_normal};
  const int id = int(sides_.size());
  sides_.push_back(s);
  front_[directed(a, b)] = id;
  for (int v : {a, b}) { Local& l = local(v); l.degree++; l.sides.push_back(id); }
  queue_.push({front_priority((out_.points[a] - out_.points[b]).Norm(), failures), id});
}

void PatchMesher::remove_side(int s) {
  Side& side = sides_[s];
  side.alive = false;
  front_.erase(directed(side.a, side.b));
  for (int v : {side.a, side.b}) {
    Local& l = local(v);
    l.degree--;
    l.sides.erase(std::remove(l.sides.begin(), l.sides.end(), s), l.sides.end());
  }
}

void PatchMesher::drop_slits() {
  std::vector<int> slits;
  for (const auto& [key, id] : front_) {
    const Side& side = sides_[id];
    if (side.a < side.b && front_.count(directed(side.b, side.a))) slits.push_back(id);
  }
  std::sort(slits.begin(), slits.end());  // (front_ is a hash map)
  for (int id : slits) {
    const int reverse = front_.at(directed(sides_[id].b, sides_[id].a));
    remove_side(id);
    remove_side(reverse);
  }
}

void PatchMesher::add_triangle(int a, int b, int c) {
  face_grid_.add(int(out_.faces.size()), (out_.points[a] + out_.points[b] + out_.points[c]) / 3.0);
  out_.faces.push_back({a, b, c});
  out_.face_patch.push_back(patch_);
  result_.faces++;
  const int tri[3] = {a, b, c};
  const Point3 n = unit_normal(out_.points[a], out_.points[b], out_.points[c]);
  for (int z = 0; z < 3; ++z) {
    const int x = tri[z], y = tri[(z + 1) % 3];
    used_.insert(directed(x, y));
    if (out_.is_shared(x, y)) out_.shared_edges.insert(OutputMesh::edge_key(x, y));
    auto it = front_.find(directed(x, y));
    if (it != front_.end()) remove_side(it->second);
    else add_side(y, x, n);
  }
}

// At a ridge or a dangling line several faces of the patch touch the side: the host is the
// face for which the side is properly oriented, i.e. the face lies to its left (Eq. 1).
int PatchMesher::side_host(int a, int b, const Projection& at_mid, const Point3& back_normal) const {
  const Surface& s = loc_.surface();
  const Point3 &pa = out_.points[a], &pb = out_.points[b];
  const Point3 mid = (pa + pb) * 0.5, dir = pb - pa;
  const double tol = at_mid.distance + 1e-7 * dir.Norm();
  std::vector<int> near;
  loc_.faces_near(mid, tol, near);
  int best = at_mid.face;
  double best_score = -2;
  for (int f : near) {
    if (s.group[f] != patch_) continue;
    // Behind a generated face the host must agree with it (no folding back over a fold of the input).
    if (back_normal.SquaredNorm() > 0 && s.face_normal[f] * back_normal <= 0.3) continue;
    const auto& t = s.faces[f];
    std::array<double, 3> bary;
    if ((closest_point_on_triangle(mid, s.points[t[0]], s.points[t[1]], s.points[t[2]], bary) - mid).Norm() > tol) continue;
    const Point3 centre = (s.points[t[0]] + s.points[t[1]] + s.points[t[2]]) / 3.0;
    Point3 left = s.face_normal[f] ^ dir;
    const double len = left.Norm();
    if (len == 0) continue;
    const double score = (left / len) * (centre - mid) / std::max((centre - mid).Norm(), 1e-300);
    if (score > best_score) { best_score = score; best = f; }
  }
  return best;
}

// A point on a line or corner touches several faces of the patch: use the normal of the one
// that agrees best with `reference`; a free point has one host face.
const std::vector<int>& PatchMesher::faces_at(int v) const {
  auto it = faces_at_.find(v);
  if (it != faces_at_.end()) return it->second;
  const Surface& s = loc_.surface();
  const Point3& p = out_.points[v];
  std::vector<int> near, on;
  const double tol = 1e-9 * std::max(size_.max_size(), 1e-300);
  loc_.faces_near(p, tol, near);
  for (int f : near) {
    if (s.group[f] != patch_) continue;
    const auto& t = s.faces[f];
    std::array<double, 3> bary;
    if ((closest_point_on_triangle(p, s.points[t[0]], s.points[t[1]], s.points[t[2]], bary) - p).Norm() <= tol)
      on.push_back(f);
  }
  return faces_at_.emplace(v, std::move(on)).first->second;
}

Point3 PatchMesher::normal_towards(int v, const Point3& reference) const {
  const Local& l = locals_.at(v);
  if (out_.kind[v] == PointKind::Free) return l.normal;
  const Surface& s = loc_.surface();
  Point3 best = l.normal;
  double best_dot = l.normal * reference;
  for (int f : faces_at(v))
    if (s.face_normal[f] * reference > best_dot) { best_dot = s.face_normal[f] * reference; best = s.face_normal[f]; }
  return best;
}

// Is triangle (a,b,q) acceptable? All 2D tests run in the tangent plane of the host face of ab.
bool PatchMesher::valid_triangle(int a, int b, const Point3& q, int q_id, const Point3& q_normal,
                                 const TangentFrame& side_frame, double h, double min_angle_rad,
                                 const std::vector<int>& near_points) const {
  checks_ += long(near_points.size()) + 1;
  if (params_.checks_left) *params_.checks_left -= long(near_points.size()) + 1;
  const Point3 &pa = out_.points[a], &pb = out_.points[b];
  // The plane of the checks averages the side's and the candidate's surface normals, so a
  // candidate just around a tight bend is still seen ahead of the side.
  Point3 n_avg = side_frame.normal + q_normal;
  if (n_avg.Norm() < 0.5) n_avg = side_frame.normal;
  const TangentFrame frame(side_frame.origin, pb - pa, n_avg);
  const vcg::Point2d a2 = frame.to_2d(pa), b2 = frame.to_2d(pb), q2 = frame.to_2d(q);
  const double L = (pb - pa).Norm();
  if (orient_2d(a2, b2, q2) <= 1e-6 * L * L) { last_reason_ = 1; return false; }       // q must lie ahead of the side
  if (min_angle(pa, pb, q) < min_angle_rad) { last_reason_ = 2; return false; }
  if (unit_normal(pa, pb, q) * frame.normal < 0.3) { last_reason_ = 3; return false; }  // folds over the surface
  // Directed-side rules: a side of the new face either closes a front side or is new.
  const int sides[2][2] = {{b, q_id}, {q_id, a}};
  if (q_id >= 0) {
    for (const auto& s : sides) {
      const auto key = directed(s[0], s[1]);
      if (front_.count(key)) continue;
      if (edge_taken(s[0], s[1])) { last_reason_ = 4; return false; }
    }
  }
  if (q_id >= 0 && over_other_patch(a, b, q_id)) { last_reason_ = 10; return false; }
  if (q_id >= 0 && out_.kind[q_id] != PointKind::Free && !within_front_angle(q_id, a, b, frame)) { last_reason_ = 12; return false; }
  if (covers_meshed_area(pa, pb, q)) { last_reason_ = 11; return false; }
  // 2D crossing and containment against nearby front sides and points on the same side of the surface.
  const double eps = 1e-9 * L * L;
  const double reach = std::max({L, (q - pa).Norm(), (q - pb).Norm()}) + h;
  for (int v : near_points) {
    auto it = locals_.find(v);
    if (it == locals_.end() || it->second.degree == 0) continue;
    const Local& l = it->second;
    if (normal_towards(v, frame.normal) * frame.normal <= 0.0) continue;  // the other side of a cusp or thin wall
    const Point3& pv = out_.points[v];
    if (std::abs((pv - frame.origin) * frame.normal) > reach) continue;
    const vcg::Point2d v2 = frame.to_2d(pv);
    if (v != a && v != b && v != q_id) {
      if (strictly_inside_2d(v2, a2, b2, q2, eps)) { last_reason_ = 5; return false; }
      // A front point (nearly) on a new side: the side would run along the front.
      auto near_segment = [&](const vcg::Point2d& x, const vcg::Point2d& y) {
        const vcg::Point2d d = y - x;
        const double len2 = d.SquaredNorm();
        if (len2 == 0) return false;
        const double t = ((v2 - x) * d) / len2;
        return t > 0 && t < 1 && (x + d * t - v2).Norm() < 0.05 * std::sqrt(len2);
      };
      if (near_segment(a2, q2) || near_segment(q2, b2)) { last_reason_ = 9; return false; }
    }
    for (int s : l.sides) {
      const Side& side = sides_[s];
      if (side.a != v) continue;  // each side once, from its first end
      const int u = side.b;
      auto iu = locals_.find(u);
      if (iu != locals_.end() && normal_towards(u, frame.normal) * frame.normal <= 0.0) continue;
      const vcg::Point2d u2 = frame.to_2d(out_.points[u]);
      auto touches = [&](int x, int y) { return x == v || x == u || y == v || y == u; };
      if (!touches(a, q_id) && segments_cross_2d(a2, q2, v2, u2, eps)) { last_reason_ = 6; return false; }
      if (!touches(q_id, b) && segments_cross_2d(q2, b2, v2, u2, eps)) { last_reason_ = 7; return false; }
      // A new point must not sit on top of a front side either.
      if (q_id < 0) {
        const vcg::Point2d d = u2 - v2;
        const double len2 = d.SquaredNorm();
        if (len2 > 0) {
          const double t = std::clamp(((q2 - v2) * d) / len2, 0.0, 1.0);
          if ((v2 + d * t - q2).Norm() < 0.3 * h) { last_reason_ = 8; return false; }
        }
      }
    }
  }
  return true;
}

// The front separates meshed from unmeshed only where it sees itself. Across a bend sharper
// than its normal filters (a coarse input with tight bends, a smooth surface bending by more than
// 60 degrees within one element) or where a side has lost its way, two parts of the front pass
// each other and faces are laid over faces already made: a second layer (the rocker-arm without
// ridges came out at 7.9x its area, the bunny as one patch at 5.9x). So no new face may lie over
// a generated face: neither its centroid nor its new corner.
bool PatchMesher::covers_meshed_area(const Point3& a, const Point3& b, const Point3& c) const {
  const Point3 n = unit_normal(a, b, c);
  for (const Point3& p : {(a + b + c) / 3.0, c})
    if (over_generated_face(p, n)) return true;
  return false;
}

// Does new face (a,b,q) point, at the front point q, into the part still to mesh: does its middle
// direction there lie between one of q's outgoing sides and, turning counterclockwise, one of its
// incoming sides? The crossing tests skip the sides that end at q, so without this a face could
// join a line or corner point from outside the patch's angle there: the front then closed a fan
// all round the point, apart from the fans of the patches beside it (fuzz_union --models seed
// 40: three non-manifold points). The middle direction, not the whole face, so that a face a
// little over a side in q's plane (at a bent corner) is still taken.
bool PatchMesher::within_front_angle(int q, int a, int b, const TangentFrame& side_frame) const {
  const auto it = locals_.find(q);
  if (it == locals_.end() || it->second.degree == 0) return true;
  // In q's own tangent plane: at a corner the side's plane can fold q's sides over.
  const Point3& pq = out_.points[q];
  const TangentFrame frame(pq, out_.points[a] - pq, normal_towards(q, side_frame.normal));
  const vcg::Point2d q2 = frame.to_2d(pq);
  auto direction = [&](int v) { return frame.to_2d(out_.points[v]) - q2; };
  auto turn = [](const vcg::Point2d& from, const vcg::Point2d& to) {  // counterclockwise, in [0, 2 pi)
    const double t = std::atan2(from[0] * to[1] - from[1] * to[0], from * to);
    return t < 0 ? t + 2 * kPi : t;
  };
  const vcg::Point2d to_a = direction(a), to_b = direction(b);
  if (to_a.SquaredNorm() == 0 || to_b.SquaredNorm() == 0) return true;
  bool judged = false;
  for (int out_side : it->second.sides) {
    if (sides_[out_side].a != q) continue;
    const vcg::Point2d to_next = direction(sides_[out_side].b);
    for (int in_side : it->second.sides) {
      if (sides_[in_side].b != q) continue;
      const vcg::Point2d to_prev = direction(sides_[in_side].a);
      if (to_next.SquaredNorm() == 0 || to_prev.SquaredNorm() == 0) continue;
      judged = true;
      const double span = sides_[in_side].a == sides_[out_side].b ? 2 * kPi : turn(to_next, to_prev);
      // The face's middle direction at q (from q->a counterclockwise to q->b) in the span.
      const double middle = std::fmod(turn(to_next, to_a) + 0.5 * turn(to_a, to_b), 2 * kPi);
      if (middle <= span) return true;
    }
  }
  return !judged;
}

bool PatchMesher::try_side(int s) {
  const int a = sides_[s].a, b = sides_[s].b, failures = sides_[s].failures;
  const Point3 &pa = out_.points[a], &pb = out_.points[b];
  const double L = (pb - pa).Norm();
  const Point3 mid = (pa + pb) * 0.5;
  const Local &la = local(a), &lb = local(b);
  const Point3 back = sides_[s].back_normal;
  const Projection host = loc_.locate(mid, patch_, back.SquaredNorm() > 0 ? back : la.normal + lb.normal, la.host >= 0 ? la.host : lb.host,
                                      L + size_.max_size());
  if (host.face < 0) return false;
  const int host_face = side_host(a, b, host, back);
  current_back_ = back;
  const Point3 normal = loc_.surface().face_normal[host_face];
  const TangentFrame frame(mid, pb - pa, normal);
  const double h = size_.at(host.face, host.bary);
  const double hs = std::clamp(h, 0.7 * L, 1.6 * L);
  double height = std::sqrt(std::max(hs * hs - 0.25 * L * L, 0.0));
  if (failures >= 2) height *= 0.6;

  // The ideal point for a well-shaped face, projected onto the patch.
  const Point3 ideal = mid + frame.e2 * height;
  Projection proj = loc_.locate(ideal, patch_, normal, host_face, 2 * hs + h);
  // Where the surface bends away within one element the projection falls short: march on
  // along the surface until the point is about `height` from the side.
  for (int step = 0; step < 3 && proj.face >= 0; ++step) {
    const Point3 dir = proj.point - mid;
    const double d = dir.Norm();
    if (d >= 0.9 * height || d <= 1e-12 * L) break;
    const Point3 nf = loc_.surface().face_normal[proj.face];
    const Projection next = loc_.locate(proj.point + dir / d * (height - d), patch_, nf, proj.face, 2 * hs + h);
    if (next.face < 0) break;
    proj = next;
  }
  const bool have_new = proj.face >= 0 && loc_.surface().face_normal[proj.face] * normal > 0.2;
  const Point3 p_new = have_new ? proj.point : ideal;
  const Point3 new_normal = have_new ? loc_.surface().face_normal[proj.face] : normal;

  const double radius = std::max(hs, L) * (2.0 + failures);
  std::vector<int> near;
  grid_.for_each_near(mid, radius + hs, [&](int v) {
    auto it = locals_.find(v);
    if (it != locals_.end() && it->second.degree > 0) near.push_back(v);
  });
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());

  // Candidates: existing front points by distance to the ideal point, the new point in between.
  const double accept_radius = params_.prefer_existing * hs * (1.0 + 0.7 * failures);
  std::vector<std::pair<double, int>> existing;
  double closest_to_new = std::numeric_limits<double>::max();
  for (int v : near) {
    if (v == a || v == b) continue;
    if (normal_towards(v, normal) * normal <= 0.2) continue;  // cusp filter by normals
    const double d = (out_.points[v] - p_new).Norm();
    closest_to_new = std::min(closest_to_new, d);
    if ((out_.points[v] - mid).Norm() <= radius) existing.push_back({d, v});
  }
  std::sort(existing.begin(), existing.end());
  const double min_angle_rad = (failures == 0 ? 20.0 : failures == 1 ? 10.0 : failures == 2 ? 3.0 : 0.5) * kDeg;
  const bool new_allowed = have_new && closest_to_new >= params_.min_point_distance * hs;

  auto accept = [&](int q) {
    add_triangle(a, b, q);
    return true;
  };
  size_t k = 0;
  for (; k < existing.size() && existing[k].first <= accept_radius; ++k) {
    const int q = existing[k].second;
    if (valid_triangle(a, b, out_.points[q], q, normal_towards(q, normal), frame, h, min_angle_rad, near)) return accept(q);
  }
  if (new_allowed && valid_triangle(a, b, p_new, -1, new_normal, frame, h, std::min(min_angle_rad, 20.0 * kDeg), near)) {
    const int q = out_.add_point(p_new, proj.face, PointKind::Free);
    result_.new_points++;
    local(q);
    return accept(q);
  }
  // Farther points, but none that would make a side much longer than the size: with the
  // search radius growing with the side and the retries, such sides made longer ones in turn
  // (armadillo at 1% with min_line_length 2%: faces up to 48 x target, left to local repair).
  const double longest = std::max(kFarCandidate * h, 1.5 * L);
  for (; k < existing.size(); ++k) {
    const int q = existing[k].second;
    if (std::max((out_.points[q] - pa).Norm(), (out_.points[q] - pb).Norm()) > longest) continue;
    if (valid_triangle(a, b, out_.points[q], q, normal_towards(q, normal), frame, h, min_angle_rad, near)) return accept(q);
  }
  return false;
}

void PatchMesher::seed_triangle() {
  // The largest face of the patch hosts an equilateral triangle of the local size.
  const Surface& s = loc_.surface();
  int best = -1;
  double best_area = -1;
  for (int f = 0; f < int(s.faces.size()); ++f) {
    if (s.group[f] != patch_) continue;
    const auto& t = s.faces[f];
    const double area = ((s.points[t[1]] - s.points[t[0]]) ^ (s.points[t[2]] - s.points[t[0]])).Norm();
    if (area > best_area) { best_area = area; best = f; }
  }
  if (best < 0) return;
  const auto& t = s.faces[best];
  const Point3 centre = (s.points[t[0]] + s.points[t[1]] + s.points[t[2]]) / 3.0;
  const double h = size_.at(best, {1.0 / 3, 1.0 / 3, 1.0 / 3});
  const TangentFrame frame(centre, s.points[t[1]] - s.points[t[0]], s.face_normal[best]);
  int ids[3];
  for (int k = 0; k < 3; ++k) {
    const double angle = (90.0 + 120.0 * k) * kDeg;
    const Point3 p = centre + (frame.e1 * std::cos(angle) + frame.e2 * std::sin(angle)) * (h / std::sqrt(3.0));
    const Projection pr = loc_.locate(p, patch_, s.face_normal[best], best, 2 * h);
    ids[k] = out_.add_point(pr.face >= 0 ? pr.point : p, pr.face >= 0 ? pr.face : best, PointKind::Free);
    result_.new_points++;
  }
  add_triangle(ids[0], ids[1], ids[2]);
}

// Would a new face edge x->y (not closing a front side) duplicate an edge? Within the patch any
// generated edge or reversed front side; across patches an edge between shared points.
bool PatchMesher::edge_taken(int x, int y) const {
  if (used_.count(directed(x, y)) || used_.count(directed(y, x)) || front_.count(directed(y, x))) return true;
  return out_.is_shared(x, y) && out_.shared_edges.count(OutputMesh::edge_key(x, y)) > 0;
}

// Does p lie over a generated face of this patch: within a quarter of the face's longest side
// of its plane, inside it (by a small margin), with a normal agreeing with `normal`?
bool PatchMesher::over_generated_face(const Point3& p, const Point3& normal) const {
  bool over = false;
  face_grid_.for_each_near(p, size_.max_size(), [&](int f) {
    if (over) return;
    const auto& t = out_.faces[f];
    const Point3 &x = out_.points[t[0]], &y = out_.points[t[1]], &z = out_.points[t[2]];
    const Point3 n = unit_normal(x, y, z);
    if (n * normal < 0.5) return;
    const double longest = std::max({(y - x).Norm(), (z - y).Norm(), (x - z).Norm()});
    if (std::abs((p - x) * n) > 0.25 * longest) return;
    std::array<double, 3> bary;
    closest_point_on_triangle(p, x, y, z, bary);
    over = bary[0] > 0.02 && bary[1] > 0.02 && bary[2] > 0.02;
  });
  return over;
}

// A patch bounded by just three line sides (a tiny island of a noisy scan) owns its one face;
// the patch around it sees the same three points as a loop of its own front and, where the scan
// folds, that loop can look fillable: filling it would cover the island twice.
bool PatchMesher::over_other_patch(int a, int b, int c) const {
  const auto it = out_.island_triangles.find(OutputMesh::triangle_key(a, b, c));
  return it != out_.island_triangles.end() && it->second != patch_;
}

// Closes loops of front sides by ear clipping: the last resort for what the front could not
// close (tiny folds of a noisy scan; loops of at most `max_sides` sides, longer ones stay open and
// are reported), and the whole meshing of a thin strip, where clipping the best-shaped ears from
// its ends zips its two lines together. Loops are split at repeated points; no edge is reused,
// so the output stays manifold.
void PatchMesher::close_loops(size_t max_sides) {
  std::unordered_map<int, std::vector<int>> outgoing;  // point -> alive sides leaving it
  for (const auto& [key, s] : front_) outgoing[sides_[s].a].push_back(s);
  for (auto& [v, list] : outgoing) std::sort(list.begin(), list.end());  // deterministic order
  std::unordered_set<int> visited;
  std::vector<int> sorted_sides;
  for (const auto& [key, s] : front_) sorted_sides.push_back(s);
  std::sort(sorted_sides.begin(), sorted_sides.end());
  std::vector<std::vector<int>> loops;
  for (int start : sorted_sides) {
    if (visited.count(start)) continue;
    // Walk the sides; a point met twice closes a simple loop, which is cut out of the path.
    std::vector<int> path{sides_[start].a};
    std::unordered_map<int, size_t> position{{sides_[start].a, 0}};
    int s = start;
    bool closed = false;
    while (s >= 0 && !visited.count(s)) {
      visited.insert(s);
      const int b = sides_[s].b;
      auto at = position.find(b);
      if (at != position.end()) {
        loops.emplace_back(path.begin() + long(at->second), path.end());
        for (size_t k = at->second + 1; k < path.size(); ++k) position.erase(path[k]);
        path.resize(at->second + 1);
        closed = path.size() == 1;
      } else {
        position[b] = path.size();
        path.push_back(b);
      }
      s = -1;
      for (int next : outgoing[b]) if (!visited.count(next)) { s = next; break; }
      if (closed && s < 0) break;
    }
  }
  for (auto& loop : loops) {
    if (loop.size() < 3 || (loop.size() > max_sides && !thin_line_loop(loop))) continue;
    // Only a loop running counter-clockwise about the surface bounds a hole to fill; a clockwise
    // one goes around something already meshed (another patch) and filling it would cover it twice.
    Point3 area(0, 0, 0), normal(0, 0, 0);
    for (size_t k = 0; k < loop.size(); ++k) {
      area += out_.points[loop[k]] ^ out_.points[loop[(k + 1) % loop.size()]];
      normal += local(loop[k]).normal;
    }
    // Three sides never go around another patch's faces (an island owns its triangle, checked
    // when closing): where the scan folds the summed normals can disagree, close them anyway.
    if (area * normal > 0 || loop.size() == 3) close_loop(std::move(loop));
  }
}

// A loop of line and corner points only, narrower (twice its area over its perimeter) than
// kThinLoop x its mean side: a strip between two lines that no front row fits in, zipped like a
// thin patch whatever its length. (fuzz_union --models seed 84 at 2%: a strip 0.00014 wide and
// 0.6 long between two intersection lines, with one input vertex off the lines so not taken for a
// thin patch, stayed open with 31 sides.)
bool PatchMesher::thin_line_loop(const std::vector<int>& loop) const {
  Point3 area(0, 0, 0);
  double perimeter = 0;
  for (size_t k = 0; k < loop.size(); ++k) {
    if (out_.kind[loop[k]] == PointKind::Free) return false;
    const Point3 &p = out_.points[loop[k]], &q = out_.points[loop[(k + 1) % loop.size()]];
    area += p ^ q;
    perimeter += (q - p).Norm();
  }
  return perimeter > 0 && area.Norm() / perimeter < kThinLoop * perimeter / double(loop.size());
}

// Ear clipping of one simple loop (the unmeshed part lies to its left): the ear with the largest
// smallest angle (looking one ear ahead) whose new side is not taken and that lies over this
// patch, preferring ears that agree with the surface normal.
void PatchMesher::close_loop(std::vector<int> loop) {
  std::vector<std::pair<double, size_t>> ears;
  while (loop.size() > 3) {
    const size_t n = loop.size();
    ears.clear();
    for (size_t i = 0; i < n; ++i) {
      const int a = loop[(i + n - 1) % n], b = loop[i], c = loop[(i + 1) % n];
      if (a == c || edge_taken(c, a)) continue;
      const Point3 &pa = out_.points[a], &pb = out_.points[b], &pc = out_.points[c];
      const Point3 surface_normal = local(a).normal + local(b).normal + local(c).normal;
      // (A flat ear has no normal of its own: the rounding's would agree half the time.)
      const double angle = min_angle(pa, pb, pc);
      const double agree = angle > kFlatEar && unit_normal(pa, pb, pc) * surface_normal > 0 ? 1.0 : 0.0;
      // One step ahead: an ear that leaves only flat ears beside it (three points on one line,
      // as where a strip's zipper meets) is worth no more than they are, agreeing or not: it
      // ends in a flat face, a last choice.
      const Point3 &pl = out_.points[loop[(i + n - 2) % n]], &pr = out_.points[loop[(i + 2) % n]];
      const double ahead = std::max(min_angle(pl, pa, pc), min_angle(pa, pc, pr));
      ears.push_back({(ahead > kFlatEar ? agree * 10.0 : 0.0) + std::min(angle, ahead), i});
    }
    // Best first; the costlier check against other patches only until one passes.
    std::sort(ears.begin(), ears.end(), std::greater<>());
    size_t chosen = n;
    for (const auto& [score, i] : ears)
      if (!over_other_patch(loop[(i + n - 1) % n], loop[i], loop[(i + 1) % n])) { chosen = i; break; }
    // Only flat ears, or ears that leave one (the diagonals that would not are edges elsewhere,
    // fuzz_union --models seed 72: a face with three points on one line): a point inside, where
    // it makes proper faces.
    if (chosen == n) { fan_from_centre(loop); return; }
    if (ears.front().first <= kFlatEar && fan_from_centre(loop, kFlatEar)) return;
    add_triangle(loop[(chosen + n - 1) % n], loop[chosen], loop[(chosen + 1) % n]);
    loop.erase(loop.begin() + long(chosen));
  }
  if (!over_other_patch(loop[0], loop[1], loop[2])) add_triangle(loop[0], loop[1], loop[2]);
}

// A loop no ear can close (where the scan folds, its diagonals are edges elsewhere already):
// a new point at its centre, projected onto the patch, and a fan of faces to it; every new
// edge ends at the new point, so none is taken.
bool PatchMesher::fan_from_centre(const std::vector<int>& loop, double must_beat) {
  Point3 centre(0, 0, 0), normal(0, 0, 0);
  for (int v : loop) { centre += out_.points[v]; normal += local(v).normal; }
  centre /= double(loop.size());
  const Projection pr = loc_.locate(centre, patch_, normal, local(loop[0]).host, size_.max_size());
  const int host = pr.face >= 0 ? pr.face : local(loop[0]).host;
  if (host < 0) return false;
  const Point3 p = pr.face >= 0 ? pr.point : centre;
  // (A loop on one line, a strip of no width, has no point that makes proper faces either.)
  double worst = std::numeric_limits<double>::max();
  for (size_t k = 0; k < loop.size(); ++k)
    worst = std::min(worst, min_angle(out_.points[loop[k]], out_.points[loop[(k + 1) % loop.size()]], p));
  if (worst <= must_beat) return false;
  const int c = out_.add_point(p, host, PointKind::Free);
  result_.new_points++;
  local(c);
  for (size_t k = 0; k < loop.size(); ++k) add_triangle(loop[k], loop[(k + 1) % loop.size()], c);
  return true;
}

double PatchMesher::estimated_faces() const {
  const Surface& s = loc_.surface();
  double area = 0;
  for (size_t f = 0; f < s.faces.size(); ++f)
    if (s.group[f] == patch_) {
      const auto& t = s.faces[f];
      area += 0.5 * ((s.points[t[1]] - s.points[t[0]]) ^ (s.points[t[2]] - s.points[t[0]])).Norm();
    }
  const double h = std::max(size_.min_size(), 1e-300);
  return area / (0.25 * std::sqrt(3.0) * h * h);
}

FrontResult PatchMesher::run(std::vector<FrontSide> front) {
  for (int f : params_.meshed_faces) {
    const auto& t = out_.faces[f];
    face_grid_.add(f, (out_.points[t[0]] + out_.points[t[1]] + out_.points[t[2]]) / 3.0);
    for (int z = 0; z < 3; ++z) used_.insert(directed(t[z], t[(z + 1) % 3]));
  }
  for (const auto& s : front)
    if (s[0] != s[1] && !front_.count(directed(s[0], s[1]))) add_side(s[0], s[1]);
  if (params_.thin_patch) {
    // No front layer fits: one layer of faces straight between the boundary lines.
    close_loops(std::numeric_limits<size_t>::max());
    drop_slits();
    result_.unmeshed_sides = int(front_.size());
    return result_;
  }
  if (front_.empty()) seed_triangle();
  const double limit = 20.0 * (estimated_faces() + double(sides_.size())) + 1000.0;
  while (!queue_.empty()) {
    if (++result_.iterations > limit || checks_ > kChecksPerStep * limit ||
        (params_.checks_left && *params_.checks_left <= 0)) {
      result_.iteration_limit = true;
      break;
    }
    const auto [priority, s] = queue_.top();
    queue_.pop();
    (void)priority;
    if (!sides_[s].alive) continue;
    if (try_side(s)) continue;
    // No valid face: retry later with relaxed checks, or give up on this side.
    if (sides_[s].failures < params_.max_retries) {
      sides_[s].failures++;
      const double len = (out_.points[sides_[s].a] - out_.points[sides_[s].b]).Norm();
      queue_.push({front_priority(len, sides_[s].failures), s});
    }
  }
  if (!front_.empty()) close_loops(kMaxLastResortLoop);
  drop_slits();
  result_.unmeshed_sides = int(front_.size());
  for (const auto& [key, id] : front_) result_.open_sides.push_back({sides_[id].a, sides_[id].b});
  std::sort(result_.open_sides.begin(), result_.open_sides.end());  // front_ is a hash map
  return result_;
}

}  // namespace

FrontResult advance_front(OutputMesh& out, std::vector<FrontSide> front, int patch, const SurfaceLocator& locator,
                          const SizeField& size, const FrontParams& params) {
  PatchMesher mesher(out, patch, locator, size, params);
  return mesher.run(std::move(front));
}

}  // namespace mr::remesh
