#include "union/face_triangulation.h"

#include "common/errors.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <unordered_map>
#include <unordered_set>

namespace mr::surface_union {

namespace {

uint64_t key(int a, int b) { return (uint64_t(uint32_t(a)) << 32) | uint32_t(b); }

/// Directed edge (a, b) of a face's local points -> its triangle. Most faces have a few
/// points: a dense table indexed by (a, b), one buffer per thread reused across faces
/// (only the entries a face wrote are reset), instead of a node-based hash map that
/// spent its time allocating; a hash map for faces with many points.
class EdgeTable {
public:
  void reset(int points) {
    for (int i : touched_) dense_[i] = -1;
    touched_.clear();
    map_.clear();
    use_dense_ = points <= kDense;
    if (use_dense_ && dense_.empty()) dense_.assign(size_t(kDense) * kDense, -1);
  }
  int get(int a, int b) const {
    if (use_dense_) return dense_[a * kDense + b];
    auto it = map_.find(key(a, b));
    return it == map_.end() ? -1 : it->second;
  }
  void set(int a, int b, int t) {
    if (use_dense_) {
      dense_[a * kDense + b] = t;
      touched_.push_back(a * kDense + b);
    } else {
      map_[key(a, b)] = t;
    }
  }
  /// Removes (a, b) if it still belongs to triangle t.
  void erase_if(int a, int b, int t) {
    if (use_dense_) {
      if (dense_[a * kDense + b] == t) dense_[a * kDense + b] = -1;
      return;
    }
    auto it = map_.find(key(a, b));
    if (it != map_.end() && it->second == t) map_.erase(it);
  }

private:
  static constexpr int kDense = 128;
  bool use_dense_ = true;
  std::vector<int> dense_;
  std::vector<int> touched_;
  std::unordered_map<uint64_t, int> map_;
};

/// The buffers of a face's triangulation, one set per thread reused by all its faces
/// (allocating them per face cost a fifth of the step).
struct TriangulatorScratch {
  EdgeTable edges;
  std::vector<int> ids, on;
  std::unordered_map<int, int> local_of;  // for faces with many points
  std::vector<std::array<int, 3>> tri;
  std::vector<std::array<int, 2>> segs, split, constraints;
  std::vector<long> changed_at, cleared_at;  // improve()'s
};

class FaceTriangulator {
public:
  FaceTriangulator(const PointTable& points, const std::array<int, 3>& corners, TriangulatorScratch& scratch,
                   std::vector<FaceCrossing>& crossings)
      : pts_(points), pr_(face_projection(points[corners[0]], points[corners[1]], points[corners[2]])),
        scratch_(scratch), ids_(scratch.ids), local_of_(scratch.local_of), tri_(scratch.tri), edge_(scratch.edges),
        segs_(scratch.constraints), crossings_(crossings) {
    ids_.assign(corners.begin(), corners.end());
    local_of_.clear();
  }

  void run(const FaceConstraints& c, std::vector<std::array<int, 3>>& out);

private:
  // ids_ >= 0: point-table index; -1 - k: crossings_[k] (not in the table yet).
  const QPoint& P(int local) const {
    const int id = ids_[local];
    return id >= 0 ? pts_[id] : crossings_[size_t(-1 - id)].point;
  }
  int orient(int a, int b, int c) const {
    // The filter decides most; where it cannot, edge crossings known to lie on their
    // edge need no exact arithmetic.
    const int s = orient2d_filter(P(a), P(b), P(c), pr_.i, pr_.j);
    if (s != 2) return s;
    if (ids_[a] >= 0 && ids_[b] >= 0 && ids_[c] >= 0 && pts_.known_collinear(ids_[a], ids_[b], ids_[c])) return 0;
    return orient2d(P(a), P(b), P(c), pr_.i, pr_.j);
  }
  /// The boxes of segments (a, b) and (u, v) are apart in the projection (strictly on
  /// the truncated doubles, which are monotone: then also on the rationals).
  bool boxes_apart(int a, int b, int u, int v) const {
    for (int k : {pr_.i, pr_.j})
      if (std::max(P(a).d[k], P(b).d[k]) < std::min(P(u).d[k], P(v).d[k]) ||
          std::max(P(u).d[k], P(v).d[k]) < std::min(P(a).d[k], P(b).d[k]))
        return true;
    return false;
  }
  /// The local index of point-table index (or crossing) `id`, added if new. Faces have
  /// a few points, found by a scan; a map once there are many.
  int local(int id) {
    if (ids_.size() <= kScanned) {
      for (size_t k = 0; k < ids_.size(); ++k)
        if (ids_[k] == id) return int(k);
    } else {
      if (local_of_.empty())
        for (size_t k = 0; k < ids_.size(); ++k) local_of_[ids_[k]] = int(k);
      const auto it = local_of_.find(id);
      if (it != local_of_.end()) return it->second;
      local_of_[id] = int(ids_.size());
    }
    ids_.push_back(id);
    return int(ids_.size()) - 1;
  }
  static constexpr size_t kScanned = 32;
  bool in_box(int p, int a, int b) const;
  bool between(int p, int a, int b) const;
  /// The segments (a, b) split at the points on them, sorted and unique, into `out`.
  void split_at_points(const std::vector<std::array<int, 2>>& segs, std::vector<std::array<int, 2>>& out) const;
  bool add_crossings(const std::vector<std::array<int, 2>>& segs);
  void insert_point(int p);
  void recover(int a, int b);
  void improve();
  bool crosses(int a, int b, int u, int v) const;
  int third(int t, int u, int v) const;
  void set_tri(int t, int a, int b, int c);
  void clear_tri(int t);
  int new_tri() { tri_.push_back({-1, -1, -1}); return int(tri_.size()) - 1; }

  const PointTable& pts_;
  Projection pr_;
  TriangulatorScratch& scratch_;
  std::vector<int>& ids_;  // local -> point-table index
  std::unordered_map<int, int>& local_of_;  // its inverse, once ids_ is longer than kScanned
  std::vector<std::array<int, 3>>& tri_;
  EdgeTable& edge_;  // directed edge -> triangle
  std::vector<std::array<int, 2>>& segs_;  // the constraints (min, max), sorted: never flipped
  std::vector<FaceCrossing>& crossings_;
};

bool FaceTriangulator::in_box(int p, int a, int b) const {
  for (int k : {pr_.i, pr_.j})
    if (P(p).d[k] < std::min(P(a).d[k], P(b).d[k]) || P(p).d[k] > std::max(P(a).d[k], P(b).d[k])) return false;
  return true;
}

// p strictly inside segment (a, b), given that it is collinear.
bool FaceTriangulator::between(int p, int a, int b) const {
  for (int k : {pr_.i, pr_.j}) {
    const int ca = compare(P(a), P(b), k);
    if (ca == 0) continue;
    const int s1 = compare(P(a), P(p), k), s2 = compare(P(p), P(b), k);
    return s1 == ca && s2 == ca;
  }
  return false;
}

void FaceTriangulator::split_at_points(const std::vector<std::array<int, 2>>& segs,
                                       std::vector<std::array<int, 2>>& out) const {
  out.clear();
  const int n = int(ids_.size());
  std::vector<int>& on = scratch_.on;
  for (const auto& s : segs) {
    const int a = s[0], b = s[1];
    on.clear();
    for (int p = 0; p < n; ++p)
      if (p != a && p != b && in_box(p, a, b) && orient(a, b, p) == 0 && between(p, a, b)) on.push_back(p);
    int axis = compare(P(a), P(b), pr_.i) != 0 ? pr_.i : pr_.j;
    const bool up = compare(P(a), P(b), axis) < 0;
    std::sort(on.begin(), on.end(), [&](int x, int y) { return compare(P(x), P(y), axis) < 0; });
    if (!up) std::reverse(on.begin(), on.end());
    int prev = a;
    for (int p : on) { out.push_back({std::min(prev, p), std::max(prev, p)}); prev = p; }
    out.push_back({std::min(prev, b), std::max(prev, b)});
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

bool FaceTriangulator::crosses(int a, int b, int u, int v) const {
  if (u == a || u == b || v == a || v == b || boxes_apart(a, b, u, v)) return false;
  const int o1 = orient(a, b, u), o2 = orient(a, b, v);
  if (o1 * o2 >= 0) return false;
  const int o3 = orient(u, v, a), o4 = orient(u, v, b);
  return o3 * o4 < 0;
}

bool FaceTriangulator::add_crossings(const std::vector<std::array<int, 2>>& segs) {
  bool any = false;
  const size_t n = segs.size();
  for (size_t x = 0; x < n; ++x)
    for (size_t y = x + 1; y < n; ++y) {
      const int a = segs[x][0], b = segs[x][1], c = segs[y][0], d = segs[y][1];
      if (!crosses(a, b, c, d)) continue;
      // Every crossing is recorded (with the lines it lies on, so splitting segments at
      // it needs no arithmetic later); one equal to a point the face already has adds
      // no local point.
      QPoint q = segment_line_crossing(P(a), P(b), P(c), P(d), pr_.i, pr_.j);
      int existing = -1;
      for (int l = 0; l < int(ids_.size()) && existing < 0; ++l)
        if (same_point(P(l), q)) existing = l;
      crossings_.push_back({std::move(q), ids_[a], ids_[b], ids_[c], ids_[d]});
      if (existing < 0) local(-int(crossings_.size()));  // a new id: added
      any = true;
    }
  return any;
}

int FaceTriangulator::third(int t, int u, int v) const {
  for (int x : tri_[t])
    if (x != u && x != v) return x;
  return -1;
}

void FaceTriangulator::set_tri(int t, int a, int b, int c) {
  tri_[t] = {a, b, c};
  edge_.set(a, b, t);
  edge_.set(b, c, t);
  edge_.set(c, a, t);
}

void FaceTriangulator::clear_tri(int t) {
  const auto& v = tri_[t];
  for (int z = 0; z < 3; ++z) {
    edge_.erase_if(v[z], v[(z + 1) % 3], t);
  }
}

void FaceTriangulator::insert_point(int p) {
  for (int t = 0; t < int(tri_.size()); ++t) {
    const auto v = tri_[t];
    int o[3];
    bool outside = false;
    for (int z = 0; z < 3 && !outside; ++z) {
      o[z] = orient(v[z], v[(z + 1) % 3], p);
      outside = o[z] < 0;
    }
    if (outside) continue;
    int on = -1;
    for (int z = 0; z < 3; ++z)
      if (o[z] == 0) on = z;
    if (on < 0) {
      clear_tri(t);
      set_tri(t, v[0], v[1], p);
      set_tri(new_tri(), v[1], v[2], p);
      set_tri(new_tri(), v[2], v[0], p);
      return;
    }
    const int a = v[on], b = v[(on + 1) % 3], c = v[(on + 2) % 3];
    const int u = edge_.get(b, a);
    clear_tri(t);
    set_tri(t, a, p, c);
    set_tri(new_tri(), p, b, c);
    if (u >= 0) {
      const int d = third(u, a, b);
      clear_tri(u);
      set_tri(u, b, p, d);
      set_tri(new_tri(), p, a, d);
    }
    return;
  }
  throw AlgorithmFailure("union: an intersection point fell outside its face (internal error)");
}

void FaceTriangulator::recover(int a, int b) {
  if (edge_.get(a, b) >= 0 || edge_.get(b, a) >= 0) return;
  std::deque<std::array<int, 2>> queue;
  for (const auto& v : tri_)
    for (int z = 0; z < 3; ++z) {
      const int u = v[z], w = v[(z + 1) % 3];
      if (u < w && crosses(a, b, u, w)) queue.push_back({u, w});
    }
  size_t guard = 0;
  const size_t limit = 100 * (queue.size() + 10) * (queue.size() + 10);
  while (!queue.empty()) {
    if (++guard > limit) throw AlgorithmFailure("union: could not recover an intersection segment in a face");
    const auto [u, v] = queue.front();
    queue.pop_front();
    const int t1 = edge_.get(u, v), t2 = edge_.get(v, u);
    if (t1 < 0 || t2 < 0) continue;  // no longer an edge
    const int c = third(t1, u, v), d = third(t2, v, u);
    if (orient(u, d, c) > 0 && orient(d, v, c) > 0) {
      clear_tri(t1);
      clear_tri(t2);
      set_tri(t1, u, d, c);
      set_tri(t2, d, v, c);
      if (crosses(a, b, c, d)) queue.push_back({c, d});
    } else {
      queue.push_back({u, v});
    }
  }
}

double angle_at(const QPoint& o, const QPoint& p, const QPoint& q) {
  double u[3], v[3];
  for (int k = 0; k < 3; ++k) { u[k] = p.d[k] - o.d[k]; v[k] = q.d[k] - o.d[k]; }
  const double dot = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  const double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
  return std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), dot);
}

/// The angles at c and d opposite edge (u, v) sum to more than `limit` (just above
/// pi). The sign of sin(alpha + beta) (no atan2) decides clear cases; near pi the
/// angles are summed as before, so the decisions are the same.
bool opposite_angles_exceed(const QPoint& c, const QPoint& d, const QPoint& u, const QPoint& v, double limit) {
  double sin_cos[2][2];  // per corner: |u x v| and u . v (unnormalized), and the norm product
  double len[2];
  const QPoint* corner[2] = {&c, &d};
  for (int m = 0; m < 2; ++m) {
    double a[3], b[3];
    for (int k = 0; k < 3; ++k) { a[k] = u.d[k] - corner[m]->d[k]; b[k] = v.d[k] - corner[m]->d[k]; }
    const double cx = a[1] * b[2] - a[2] * b[1], cy = a[2] * b[0] - a[0] * b[2], cz = a[0] * b[1] - a[1] * b[0];
    sin_cos[m][0] = std::sqrt(cx * cx + cy * cy + cz * cz);
    sin_cos[m][1] = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    len[m] = std::sqrt((a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) * (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]));
  }
  const double scale = len[0] * len[1];
  if (scale > 0) {
    // sin(alpha + beta) = sin a cos b + cos a sin b; both angles in [0, pi].
    const double s = (sin_cos[0][0] * sin_cos[1][1] + sin_cos[0][1] * sin_cos[1][0]) / scale;
    if (s > 1e-6) return false;  // alpha + beta < pi
    if (s < -1e-6) return true;  // pi + 1e-6 < alpha + beta < 2 pi
  }
  return angle_at(c, u, v) + angle_at(d, u, v) > limit;
}

// Flips unconstrained edges towards Delaunay, measured in 3D (the projection distorts angles).
void FaceTriangulator::improve() {
  const double pi = 3.14159265358979323846;
  // A triangle whose edges all kept their shape since it was last found to have none to
  // flip still has none: the decision reads only the two triangles of an edge. Flips
  // move the clock; each triangle keeps when it last changed and when it was last cleared.
  std::vector<long>& changed_at = scratch_.changed_at;
  std::vector<long>& cleared_at = scratch_.cleared_at;
  changed_at.assign(tri_.size(), 0);
  cleared_at.assign(tri_.size(), -1);
  long clock = 0;
  auto still_clear = [&](int t) {
    if (cleared_at[size_t(t)] < changed_at[size_t(t)]) return false;
    for (int z = 0; z < 3; ++z) {
      const int t2 = edge_.get(tri_[t][(z + 1) % 3], tri_[t][z]);
      if (t2 >= 0 && changed_at[size_t(t2)] > cleared_at[size_t(t)]) return false;
    }
    return true;
  };
  for (int pass = 0; pass < 50; ++pass) {
    int flips = 0;
    for (int t1 = 0; t1 < int(tri_.size()); ++t1) {
      if (still_clear(t1)) continue;
      bool flipped = false;
      for (int z = 0; z < 3; ++z) {
        const int u = tri_[t1][z], v = tri_[t1][(z + 1) % 3];
        if (std::binary_search(segs_.begin(), segs_.end(), std::array<int, 2>{std::min(u, v), std::max(u, v)}))
          continue;
        const int t2 = edge_.get(v, u);
        if (t2 < 0) continue;
        const int c = third(t1, u, v), d = third(t2, v, u);
        if (!opposite_angles_exceed(P(c), P(d), P(u), P(v), pi + 1e-9)) continue;
        if (!(orient(u, d, c) > 0 && orient(d, v, c) > 0)) continue;
        clear_tri(t1);
        clear_tri(t2);
        set_tri(t1, u, d, c);
        set_tri(t2, d, v, c);
        changed_at[size_t(t1)] = changed_at[size_t(t2)] = ++clock;
        ++flips;
        flipped = true;
        break;
      }
      if (!flipped) cleared_at[size_t(t1)] = clock;
    }
    if (flips == 0) break;
  }
}

void FaceTriangulator::run(const FaceConstraints& c, std::vector<std::array<int, 3>>& out) {
  std::vector<std::array<int, 2>>& segs = scratch_.segs;
  std::vector<std::array<int, 2>>& split = scratch_.split;
  segs.clear();
  for (int p : c.points) local(p);
  for (const auto& s : c.segments) {
    const int a = local(s[0]), b = local(s[1]);
    if (a != b) segs.push_back({std::min(a, b), std::max(a, b)});
  }
  std::sort(segs.begin(), segs.end());
  segs.erase(std::unique(segs.begin(), segs.end()), segs.end());
  split_at_points(segs, split);
  segs.swap(split);
  if (add_crossings(segs)) {
    split_at_points(segs, split);
    segs.swap(split);
  }

  tri_.clear();
  edge_.reset(int(ids_.size()));
  tri_.push_back({-1, -1, -1});
  set_tri(0, 0, 1, 2);
  for (int p = 3; p < int(ids_.size()); ++p) insert_point(p);
  for (const auto& s : segs) recover(s[0], s[1]);
  segs_.swap(segs);  // sorted and unique (split_at_points)
  improve();
  for (const auto& v : tri_) out.push_back({ids_[v[0]], ids_[v[1]], ids_[v[2]]});
}

}  // namespace

void triangulate_face(const PointTable& points, const std::array<int, 3>& corners, const FaceConstraints& c,
                      FaceTriangles& out) {
  out.triangles.clear();
  out.crossings.clear();
  thread_local TriangulatorScratch scratch;
  FaceTriangulator(points, corners, scratch, out.crossings).run(c, out.triangles);
}

void commit_face(PointTable& points, FaceTriangles& face, std::vector<std::array<int, 3>>& out) {
  // The same calls, in the same order, as if each crossing had gone into the table when
  // it was found: equal crossings get the same index, every line is marked.
  std::vector<int> id(face.crossings.size());
  for (size_t k = 0; k < face.crossings.size(); ++k) {
    FaceCrossing& x = face.crossings[k];
    id[k] = points.insert_on_line(std::move(x.point), x.u, x.w);
    points.mark_on_line(id[k], x.c, x.d);
  }
  for (auto t : face.triangles) {
    for (int& v : t)
      if (v < 0) v = id[size_t(-1 - v)];
    out.push_back(t);
  }
}

int triangulate_face(PointTable& points, const std::array<int, 3>& corners, const FaceConstraints& c,
                     std::vector<std::array<int, 3>>& out) {
  FaceTriangles face;
  triangulate_face(points, corners, c, face);
  commit_face(points, face, out);
  return int(face.triangles.size());
}

}  // namespace mr::surface_union
