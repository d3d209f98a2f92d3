#include "union/sliver_collapse.h"

#include "union/link_triangulation.h"
#include "union/triangle_angles.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "common/flat_index_map.h"
#include "common/parallel_for.h"
#include "union/exact.h"
#include "union/face_clearance.h"
#include "union/face_tree.h"
#include "union/patch_distance.h"
#include "union/same_cover.h"
#include "union/vec3.h"

namespace mr::surface_union {

namespace {

constexpr double kPi = 3.14159265358979323846;
// A star is smooth when every face normal is within ~45 degrees of the star's mean
// normal (CAD creases of 90 degrees are not; sphere meshes and blobs are).
constexpr double kSmoothStarCos = 0.7;
// A move may trade a worse worst angle for fewer slivers only while that angle stays above this.
constexpr double kNoRatchetBelow = kPi / 180;
// Larger stars (fans of CAD plates) are left to the other moves: their link has too many triangulations to weigh each time.
constexpr int kMaxRemovedValence = 12;
// A slide along a line must raise its star's worst angle by this fraction: smaller gains
// were mostly line vertices sliding to and fro on CAD creases, pass after pass, each
// slide making the whole neighbourhood try every move again. The price: the 2000-sphere
// cluster's worst angle is 6.16 deg instead of 7.37 (asking it only of stars in two
// planes kept 7.37 but cost box.STL a fifth more work than it saves).
constexpr double kMinSlideGain = 0.1;
// Faces at a vertex whose normals differ by more than ~30 degrees: it lies on a crease.
constexpr double kCreaseCos = 0.866;
// A flat flip must raise its pair's smallest angle by this (radians), so that rounding in
// the angles cannot make two flips undo each other.
constexpr double kFlatFlipGain = 1e-9;
// Sine of the angle between two faces' normals above which they are not taken for
// coplanar without the exact test (far above the rounding of coplanar faces' normals;
// the exact test of a thin sliver against a curved neighbour needs rational arithmetic).
constexpr double kFlatSine = 1e-6;

/// Boxes [alo, ahi] and [blo, bhi] have no point in common.
inline bool boxes_apart(const V3& alo, const V3& ahi, const V3& blo, const V3& bhi) {
  return ahi[0] < blo[0] || bhi[0] < alo[0] || ahi[1] < blo[1] || bhi[1] < alo[1] || ahi[2] < blo[2] ||
         bhi[2] < alo[2];
}

/// Vertex x is a corner of face t. Written out: std::find on the three corners was an
/// out-of-line call, run a few hundred thousand times by the collapse candidates.
inline bool has_corner(const std::array<int, 3>& t, int x) { return t[0] == x || t[1] == x || t[2] == x; }


/// The surface as the cut left it, in one tree or two (two halves of it, overlapping).
struct CutSurface {
  const FaceTree* first = nullptr;
  const FaceTree* second = nullptr;
  /// FaceTree::distance's answer over both.
  double distance(const V3& p, double enough, double limit, FaceTree::Recent* recent) const {
    const double d = first->distance(p, enough, limit, recent);
    if (!second || d <= enough) return d;
    return std::min(d, second->distance(p, enough, limit, nullptr));
  }
};

/// What bounds the moves, measured on the whole surface (a part's own would differ).
struct Limits {
  double max_dev = 0;        // absolute: each move's deviation bound
  double volume_budget = 0;  // absolute: the total volume change the moves may make
  double volume = 0;         // |volume| of the whole surface
};

/// Where a collapser may change faces: those whose extent along `axis` lies strictly
/// inside (lo, hi), before and after the change. Two collapsers whose slabs are apart
/// change faces that cannot meet, and neither reads what the other changes.
struct Slab {
  int axis = -1;  // -1: everywhere
  double lo = -HUGE_VAL, hi = HUGE_VAL;
};

class Collapser {
public:
  Collapser(Result& r, const std::vector<char>& cut, const Limits& limits, SideWorker* helper,
            const CutSurface& cut_surface, Slab slab = {})
      : helper_(helper), r_(r), alive_(r.faces.size(), 1), cut_(cut), vf_(r.vertices.size()), grid_(r.vertices, r.faces),
        cut_surface_(cut_surface), slab_(slab), new_mark_(r.faces.size(), 0), angle_(r.faces.size(), -1) {
    volume_budget_ = limits.volume_budget;
    budget_scale_ = limits.volume;
    {  // Each star's list allocated once at its size (and a little room for collapses).
      std::vector<int> valence(r.vertices.size(), 0);
      for (const auto& t : r.faces)
        for (int v : t) ++valence[size_t(v)];
      for (size_t v = 0; v < vf_.size(); ++v) vf_[v].reserve(size_t(valence[v]) + 2);
    }
    for (int f = 0; f < int(r.faces.size()); ++f)
      for (int v : r.faces[f]) vf_[v].push_back(f);
    max_dev_ = limits.max_dev;
    position_index_.reserve(r.vertices.size());
    for (const V3& p : r.vertices) ++vertices_at(p);
    // Line edges and degrees.
    for (int f = 0; f < int(r.faces.size()); ++f)
      for (int z = 0; z < 3; ++z)
        if (r.line_edge[f][z]) line_.insert(ekey(r.faces[f][z], r.faces[f][(z + 1) % 3]));
    line_degree_.assign(r.vertices.size(), 0);
    for (const auto& e : line_) { ++line_degree_[e.first]; ++line_degree_[e.second]; }
  }

  /// `seed` (per vertex, or null: all): the first pass of each round only treats slivers
  /// at these vertices. `cut_distance` (per face, or null: 0): bounds on the faces'
  /// distances from the cut's surface that earlier moves left.
  int run(double threshold_rad, const std::vector<char>* seed = nullptr, const std::vector<double>* cut_distance = nullptr);
  void run_passes(double threshold_rad, const std::vector<char>* seed);
  void compact();
  /// After run(), without compacting: the faces as they are (dead ones marked), their
  /// line sides in r.line_edge and cut marks in `cut`, distances in `cut_distance`, the
  /// vertices whose moves the slab refused in `deferred`, and the volume still left.
  double hand_over(std::vector<char>& alive, std::vector<char>& cut, std::vector<double>& cut_distance,
                   std::vector<char>& deferred);

private:
  static std::pair<int, int> ekey(int a, int b) { return {std::min(a, b), std::max(a, b)}; }
  V3 P(int v) const { return r_.vertices[v]; }
  /// Smallest angle of face f, kept until the face changes (every candidate move
  /// compares the angles of the same star).
  double min_angle(int f) const {
    if (angle_[f] < 0) angle_[f] = smallest_angle(P(r_.faces[f][0]), P(r_.faces[f][1]), P(r_.faces[f][2]));
    return angle_[f];
  }
  /// Face f has new corners or a moved corner: filed again, its angle recomputed.
  void refile(int f) {
    grid_.add(f);
    angle_[f] = -1;
    touched(f);
  }
  /// Face f changed or is going: its corners' neighbourhoods are not what they were.
  void touched(int f) {
    ++clock_;
    for (int y : r_.faces[f]) changed_at_[y] = clock_;
  }
  /// No face at x or at its ring (the corners of x's live faces fx) changed after clock
  /// `at` (-1: never refused). A vertex removal or a line slide of x refused before its
  /// crossing check reads no more than that (the slide's compensating neighbours are in
  /// the ring) and the budget, which only shrinks within a round: refused then, it would
  /// be refused again. run() forgets the refusals between rounds.
  bool star_unchanged_since(long at, int x, const std::vector<int>& fx) const {
    if (at < 0 || changed_at_[x] > at) return false;
    for (int f : fx)
      for (int y : r_.faces[f])
        if (changed_at_[y] > at) return false;
    return true;
  }
  /// The collapse of v onto w was refused before its crossing check since the last change
  /// at v and at w. What that part decides reads only the stars of v and w (their faces,
  /// corners, lines and cut marks: any change there changes the clock at v or w) and the
  /// volume budget, which only shrinks within a round: it would refuse again.
  static uint64_t collapse_key(int v, int w) { return uint64_t(uint32_t(v)) << 32 | uint32_t(w); }
  bool collapse_still_refused(int v, int w) const {
    const auto it = collapse_refused_at_.find(collapse_key(v, w));
    return it != collapse_refused_at_.end() && changed_at_[v] <= it->second && changed_at_[w] <= it->second;
  }
  /// Face f with its corner x at `moved` (into q); false if it would degenerate or turn over.
  bool moved_face(int f, int x, const V3& moved, V3 q[3]) const {
    const auto& t = r_.faces[f];
    for (int z = 0; z < 3; ++z) q[z] = t[z] == x ? moved : P(t[z]);
    const V3 n_old = cross(sub3(P(t[1]), P(t[0])), sub3(P(t[2]), P(t[0])));
    const V3 n_new = cross(sub3(q[1], q[0]), sub3(q[2], q[0]));
    return norm(n_new) > 0 && dot(n_old, n_new) > 0.1 * norm(n_old) * norm(n_new);
  }
  /// Moves v onto w if allowed; with `apply` false only checks, and `dv` gets the volume change.
  bool try_collapse(int v, int w, bool apply = true, double* dv_out = nullptr);
  /// Flips side z of face f.
  bool try_flip(int f, int z) {
    return unless_refused_now(flip_refused_now_[size_t(3 * f + z)], [&] { return attempt_flip(f, z); });
  }
  bool attempt_flip(int f, int z);
  /// Before the checked moves, the input's own slivers on flat parts (CAD needles: 1261
  /// of box.STL's 8954 faces): Lawson's flips between two of the input's faces that lie
  /// exactly in one plane and form a strictly convex quad, where one of them is a sliver
  /// and the flip raises the pair's smallest angle. The quad covers the same points after
  /// the flip: no volume changes, nothing moves, nothing can come to cross, so none of
  /// the other moves' checks is needed. They start at those slivers (with a corner in
  /// `seed`, when given) and spread to the sides of each quad they change. The cut's own
  /// faces are left to the checked moves: flipping them too gave fewer faces under 5 deg
  /// on box.STL but, through the moves after it, smaller worst angles elsewhere (part.off
  /// with its turned copy 0.31 deg instead of 0.68). Returns the flips.
  int flip_flat_slivers(const std::vector<char>* seed);
  /// Flips side z of face f as above if allowed; returns the other face, or -1.
  int flat_flip(int f, int z);
  /// Face f has an angle below the threshold (its tangent given): no arc tangent.
  bool below_threshold(int f, double tan_threshold) const;
  /// A move refused at this clock (in `at`) is refused again without trying: nothing has
  /// changed since. Every change of a face moves the clock, and so does each round (the
  /// volume budget changes only with faces or between rounds). Neighbouring slivers try
  /// the same moves of their shared corners one after the other.
  template <class Attempt>
  bool unless_refused_now(long& at, Attempt attempt) {
    if (at == clock_) return false;
    if (attempt()) return true;
    at = clock_;
    return false;
  }
  std::vector<long> flip_refused_now_, removal_refused_now_, slide_refused_now_, relocation_refused_now_;
  /// Who may give back the volume a flip of (u, v) to (c, d) changes, in the order
  /// tried: the four corners, then the free vertices one ring further (after the flip),
  /// each once (a vertex that cannot give the volume back fails the same way again).
  void flip_compensators(int u, int v, int c, int d, std::vector<int>& out) const {
    out = {c, d, u, v};
    for (int x : {c, d})
      for (int h : vf_[x])
        if (alive_[h])
          for (int y : r_.faces[h])
            if (std::find(out.begin(), out.end(), y) == out.end()) out.push_back(y);
  }
  /// Where the flip of (u, v) in faces f = (u, v, c) and g = (v, u, d) changes the star
  /// lists, so that unflip() restores them exactly.
  struct FlipUndo {
    long at_u, at_v;
  };
  /// Faces f and g become (u, d, c) and (d, v, c), with the star lists to match.
  FlipUndo flip(int f, int g, int u, int v, int c, int d) {
    const FlipUndo undo{std::find(vf_[u].begin(), vf_[u].end(), g) - vf_[u].begin(),
                        std::find(vf_[v].begin(), vf_[v].end(), f) - vf_[v].begin()};
    r_.faces[f] = {u, d, c};
    r_.faces[g] = {d, v, c};
    angle_[f] = angle_[g] = -1;
    vf_[u].erase(vf_[u].begin() + undo.at_u);
    vf_[v].erase(vf_[v].begin() + undo.at_v);
    vf_[c].push_back(g);
    vf_[d].push_back(f);
    return undo;
  }
  void unflip(int f, int g, int u, int v, int c, int d, const FlipUndo& undo) {
    r_.faces[f] = {u, v, c};
    r_.faces[g] = {v, u, d};
    angle_[f] = angle_[g] = -1;
    vf_[c].pop_back();
    vf_[d].pop_back();
    vf_[u].insert(vf_[u].begin() + undo.at_u, g);
    vf_[v].insert(vf_[v].begin() + undo.at_v, f);
  }
  /// Moves free vertex x (no line) along the volume gradient of its star so
  /// that the enclosed volume changes by -dv6 / 6, when no face flips or becomes (more
  /// of) a sliver and the move stays within the deviation bound.
  bool compensate(int x, double dv6);
  /// Where compensate(x, dv6) would move x, checked but for the crossings (scratch_fx_
  /// then holds x's faces).
  bool plan_compensation(int x, double dv6, V3& moved);
  /// Moves free vertex x towards the centroid of its ring, projected so that the volume
  /// stays the same (perpendicular to its star's volume gradient), when that raises the
  /// worst angle of its faces and flips none.
  bool try_relocate(int x) {
    return unless_refused_now(relocation_refused_now_[size_t(x)], [&] { return attempt_relocation(x); });
  }
  bool attempt_relocation(int x);
  /// A triple point next to sliver corner c (a junction j joined to c by a line edge)
  /// moves onto c: the wedge between two lines leaving j is where their vertices come
  /// too close to collapse (j is a third common neighbour); after the move they are
  /// consecutive on one line and can slide together.
  bool try_junction_slide(int c);
  /// Removes v (free, or on one line with its two line neighbours then joined) and fills
  /// its star with the best triangulation of its link that uses no edge the mesh already
  /// has: where the collapse of a sliver's short edge is refused because its ends have a
  /// third common neighbour (the link condition) or a face of the fan would turn over,
  /// another triangulation of the same hole often exists.
  bool try_remove_vertex(int v) {
    return unless_refused_now(removal_refused_now_[size_t(v)], [&] { return attempt_removal(v); });
  }
  bool attempt_removal(int v);
  /// Moves x (on one line, degree 2) part of the way towards one of its two line
  /// neighbours, to the place among a few along each line edge that raises the worst
  /// angle of its faces most: where two lines pass closer than a sliver allows, their
  /// vertices can be staggered although none may leave its line.
  bool try_slide_on_line(int x) {
    return unless_refused_now(slide_refused_now_[size_t(x)], [&] { return attempt_slide_on_line(x); });
  }
  bool attempt_slide_on_line(int x);
  /// The corners of x's faces may have new options in the next pass.
  void mark_around(int x) {
    for (int f : vf_[x])
      if (alive_[f])
        for (int y : r_.faces[f]) changed_[y] = 1;
  }
  /// Two faces around x meet at more than a crease angle (CAD edges, not curved patches).
  bool on_crease(int x) const {
    V3 first{0, 0, 0};
    bool have = false;
    for (int f : vf_[x]) {
      if (!alive_[f]) continue;
      const auto& t = r_.faces[f];
      V3 n = cross(sub3(P(t[1]), P(t[0])), sub3(P(t[2]), P(t[0])));
      const double l = norm(n);
      if (!(l > 0)) continue;
      for (double& c : n) c /= l;
      if (!have) {
        first = n;
        have = true;
      } else if (dot(first, n) < kCreaseCos) {
        return true;
      }
    }
    return false;
  }
  /// Face f lies strictly inside the slab.
  bool in_slab(int f) const {
    if (slab_.axis < 0) return true;
    const auto& t = r_.faces[f];
    for (int x : t) {
      const double c = r_.vertices[x][slab_.axis];
      if (!(c > slab_.lo && c < slab_.hi)) return false;
    }
    return true;
  }
  /// Every live face at x lies inside the slab: x may move or go. Otherwise x waits for
  /// the run over the whole surface (deferred).
  bool star_in_slab(int x) {
    if (slab_.axis < 0) return true;
    for (int f : vf_[x])
      if (alive_[f] && !in_slab(f)) return defer(x);
    return true;
  }
  /// The proposed faces lie inside the slab.
  bool proposed_in_slab() {
    if (slab_.axis < 0) return true;
    for (const auto& q : new_pos_)
      for (const V3& p : q)
        if (!(p[slab_.axis] > slab_.lo && p[slab_.axis] < slab_.hi)) {
          for (int f : replaced_) for (int y : r_.faces[f]) defer(y);
          return false;
        }
    return true;
  }
  bool defer(int x) {
    if (deferred_.empty()) deferred_.assign(r_.vertices.size(), 0);
    deferred_[size_t(x)] = 1;
    return false;
  }
  /// The live face across side (u, v) of face f (it holds the side as (v, u)), or -1.
  int face_across(int f, int u, int v) const {
    int g = -1;
    for (int h : vf_[v])
      if (alive_[h] && h != f)
        for (int y = 0; y < 3; ++y)
          if (r_.faces[h][y] == v && r_.faces[h][(y + 1) % 3] == u) g = h;
    return g;
  }
  /// The corner of face g that is neither u nor v.
  int third_corner(int g, int u, int v) const {
    int d = -1;
    for (int x : r_.faces[g])
      if (x != u && x != v) d = x;
    return d;
  }
  bool edge_exists(int a, int b) const {
    for (int f : vf_[a])
      if (alive_[f] && has_corner(r_.faces[f], b)) return true;
    return false;
  }
  // A move proposes the faces it would change (new corners and positions) and lists
  // the faces it replaces; stays_clear() checks them exactly against each other and
  // every other live face nearby before the move is applied.
  void start_move() {
    replaced_.clear();
    new_ids_.clear();
    new_pos_.clear();
  }
  /// Face f with corner `from` replaced by `to` at position `at` (from == to: a move).
  void propose(int f, int from, int to, const V3& at) {
    replaced_.push_back(f);
    std::array<int, 3> t = r_.faces[f];
    std::array<V3, 3> q;
    for (int z = 0; z < 3; ++z) {
      if (t[z] == from) t[z] = to;
      q[z] = t[z] == to ? at : P(t[z]);
    }
    new_ids_.push_back(t);
    new_pos_.push_back(q);
  }
  bool stays_clear();
  /// The move's checks but the touching one: near_cut_surface(cut_pointwise), after
  /// stays_near(near_pointwise) when `compare_patches`, and stays_clear(), whose face
  /// pairs the helper starts on meanwhile (the pair tests and the deviation checks read
  /// the same state and write their own scratch).
  bool near_and_clear(double cut_pointwise, bool compare_patches = false, double near_pointwise = 1e300);
  // stays_clear() in parts: the faces near the move (near_), their tests against the
  // new faces (shared out in chunks through share_), the new faces among themselves.
  void gather_near_faces();
  bool meets_new_face(int g) const;
  void test_near_faces();
  bool new_faces_clear() const;
  struct PairShare {
    std::atomic<size_t> next{0};
    std::atomic<bool> met{false}, cancel{false};
  } share_;
  /// The proposed faces and the faces they replace are within the deviation bound of
  /// each other: `pointwise`, the farthest any point of the faces moves, when it is known
  /// and within the bound; else the two patches are compared (patch_distance.h).
  bool stays_near(double pointwise = 1e300);
  std::vector<Triangle> near_old_, near_new_;  // scratch of stays_near and of collapses
  /// Every proposed face lies within the deviation bound of the surface the cut made:
  /// the replaced faces' distance from it plus `pointwise` (how far any point of them
  /// moves, when known), or else measured at samples (moved corners, edge quarter points,
  /// centroid). Keeps the new faces' distance for keep_cut_distance().
  bool near_cut_surface(double pointwise = 1e300);
  void keep_cut_distance() {
    for (int f : replaced_) cut_distance_[f] = move_cut_distance_;
  }
  std::vector<double> cut_distance_;  // per face: bound on its distance from the cut's surface
  double move_cut_distance_ = 0;
  /// Proposed face i meets the coordinate plane x_k = c only in an old edge or an old
  /// corner of its own (unmoved, the edge there before the move), its other corners
  /// strictly on one side, or not at all. Whatever it touches of a face in that plane,
  /// the old faces along that edge or at that corner touched already: no new contact.
  bool meets_axis_plane_only_where_it_was(size_t i, int k, double c) const;
  /// The proposed move leaves the surface covering the same points (same_cover: a flat
  /// star filled again, a vertex slid along a straight crease of CAD plates), so it
  /// cannot meet anything new, unless a vertex of another sheet sits exactly where
  /// vertex `gone` (or `gone2`) was, bodies touching there: that is looked up.
  bool cover_unchanged(int gone, int gone2 = -1);
  /// Moves x (whose live faces are fx) to `at` if that stays clear of the faces nearby.
  bool move_vertex(int x, const std::vector<int>& fx, const V3& at);
  void live_faces(int v, std::vector<int>& out) const {
    out.clear();
    for (int f : vf_[v])
      if (alive_[f]) out.push_back(f);
  }
  // Reused by try_collapse (called for every candidate edge): no allocation per call.
  std::vector<int> scratch_fv_, scratch_fw_, scratch_nv_, scratch_nw_, scratch_fx_;
  // How many vertices (live or not) sit at each position: where only one does, no other
  // sheet's vertex can sit where a moved or removed vertex was (cover_unchanged).
  struct PositionHash {
    size_t operator()(const V3& p) const { return hash_position(p[0], p[1], p[2]); }
  };
  FlatIndexMap<V3, PositionHash> position_index_;
  std::vector<int> position_count_;
  int& vertices_at(const V3& p) {
    const auto [slot, added] = position_index_.emplace(p, int(position_count_.size()));
    if (added) position_count_.push_back(0);
    return position_count_[size_t(slot)];
  }
  /// Every move of a vertex goes through here.
  void place(int x, const V3& p) {
    --vertices_at(r_.vertices[x]);
    ++vertices_at(p);
    r_.vertices[x] = p;
  }
  std::vector<int> removal_faces_, removal_ring_;  // try_remove_vertex's
  std::vector<int> slide_faces_, slide_ring_;      // try_slide_on_line's
  std::vector<std::pair<int, char>> slide_marks_;
  std::vector<std::array<int, 2>> removal_sides_;
  std::vector<V3> removal_at_;
  std::vector<std::array<int, 3>> removal_tris_;
  std::vector<int> removal_sources_;
  std::vector<int> ring_mark_;  // per vertex: the stamp of the last ring it was put in
  int ring_stamp_ = 0;

  SideWorker* helper_;  // or null
  Result& r_;
  std::vector<char> alive_;
  std::vector<char> changed_;  // vertices whose neighbourhood changed in this pass
  std::vector<char> cut_;
  std::vector<std::vector<int>> vf_;
  FaceGrid grid_;  // where the faces are now, for the crossing checks
  // The surface as the cut left it: moves one after another must not take the surface
  // further from it than the deviation bound (each alone is within it). Over the faces
  // within two rings of a cut face, the only ones moves come near.
  CutSurface cut_surface_;  // shared, read only
  Slab slab_;
  std::vector<char> deferred_;  // per vertex (empty: none): a move there left the slab
  /// At the step's start: the faces' distances from the cut's surface (0) and the
  /// touching vertices.
  void keep_cut_surface();
  std::vector<char> touching_;  // per vertex: another sheet's vertex sits at its place as the step begins
  /// Where two sheets touch (vertices of both at one point), their faces keep their shape
  /// unless the cover stays the same: tilted even slightly, faces that still only touch
  /// there get flagged by MeshLab's self-intersection test.
  bool replaces_touching_face() const {
    for (int f : replaced_)
      for (int x : r_.faces[f])
        if (touching_[x]) return true;
    return false;
  }
  std::vector<int> replaced_, near_, scratch_at_v_;
  std::vector<std::array<V3, 2>> scratch_boxes_;
  std::vector<PlacedFace> scratch_before_, scratch_after_;
  std::vector<int> scratch_compensators_;
  long clock_ = 0;                        // counts face changes
  std::vector<long> changed_at_;          // per vertex: clock of the last change at it
  std::vector<long> removal_refused_at_;  // per vertex: clock of its refused removal, or -1
  std::vector<long> slide_refused_at_;    // per vertex: clock of its refused slide on a line, or -1
  std::unordered_map<uint64_t, long> collapse_refused_at_;  // (v, w): clock of the refused collapse of v onto w
  /// The last collapses dry runs accepted (a sliver weighs up to six): target (relative to
  /// w) and six times the volume change, valid while the clock stands (no face changed).
  struct Weighed {
    int v = -1, w = -1;
    long clock = -1;
    V3 p{};
    double dv = 0;
  };
  std::array<Weighed, 6> weighed_;
  size_t next_weighed_ = 0;
  std::vector<std::array<int, 3>> new_ids_;
  std::vector<std::array<V3, 3>> new_pos_;
  std::vector<int> new_mark_;  // per face: stamp of the move that replaces it
  mutable std::vector<double> angle_;  // per face: smallest angle, -1 when not known
  int new_stamp_ = 0;
  struct PairHash {
    size_t operator()(const std::pair<int, int>& e) const {
      const uint64_t h = (uint64_t(uint32_t(e.first)) << 32 | uint32_t(e.second)) * 0x9E3779B97F4A7C15ull;
      return size_t(h ^ (h >> 29));
    }
  };
  std::unordered_set<std::pair<int, int>, PairHash> line_;
  std::vector<int> line_degree_;
  double max_dev_ = 0;
  double volume_budget_ = 0;  // what the accepted moves may still change in total
  double budget_scale_ = 0;   // |volume|
  double threshold_ = 0;      // sliver angle, radians
  static double det(const V3& a, const V3& b, const V3& c) { return dot(a, cross(b, c)); }

public:
  int collapses_ = 0, flips_ = 0, flat_flips_ = 0;
};

bool Collapser::below_threshold(int f, double tan_threshold) const {
  // The smallest angle lies opposite the shortest side.
  const auto& t = r_.faces[f];
  int z = 0;
  double shortest = HUGE_VAL;
  for (int k = 0; k < 3; ++k) {
    const V3 e = sub3(P(t[(k + 1) % 3]), P(t[k]));
    if (dot(e, e) < shortest) {
      shortest = dot(e, e);
      z = k;
    }
  }
  const V3 o = P(t[(z + 2) % 3]);
  const V3 a = sub3(P(t[z]), o), b = sub3(P(t[(z + 1) % 3]), o);
  return norm(cross(a, b)) < tan_threshold * dot(a, b);
}

int Collapser::flat_flip(int f, int z) {
  const int u = r_.faces[f][z], v = r_.faces[f][(z + 1) % 3], c = r_.faces[f][(z + 2) % 3];
  if (cut_[f] || line_.count(ekey(u, v))) return -1;
  const int g = face_across(f, u, v);
  if (g < 0 || cut_[g]) return -1;
  const double before = std::min(min_angle(f), min_angle(g));
  if (!(before < threshold_)) return -1;  // the input's good faces keep their shape
  const int d = third_corner(g, u, v);
  const V3 n_f = cross(sub3(P(v), P(u)), sub3(P(c), P(u)));
  const V3 n_g = cross(sub3(P(u), P(v)), sub3(P(d), P(v)));
  if (!(dot(n_f, n_g) > 0) || norm(cross(n_f, n_g)) > kFlatSine * norm(n_f) * norm(n_g)) return -1;
  {  // Locally Delaunay already (the angles at c and d sum to at most pi): no flip raises
     // the smallest angle. Cheaper than the angles, which decide the rest.
    const V3 cu = sub3(P(u), P(c)), cv = sub3(P(v), P(c)), du = sub3(P(u), P(d)), dv = sub3(P(v), P(d));
    if (norm(cross(cu, cv)) * dot(du, dv) + dot(cu, cv) * norm(cross(du, dv)) >= 0) return -1;
  }
  const double after = std::min(smallest_angle(P(u), P(d), P(c)), smallest_angle(P(d), P(v), P(c)));
  if (!(after > before + kFlatFlipGain) || !flat_convex_quad(P(u), P(v), P(c), P(d)) || edge_exists(c, d)) return -1;
  if (!in_slab(f) || !in_slab(g)) {  // (the new faces lie within the two old ones)
    for (int h : {f, g}) for (int y : r_.faces[h]) defer(y);
    return -1;
  }
  // (Both stay the input's faces, on the cut's surface: not treated by the other moves.)
  const bool f_worse = min_angle(f) <= min_angle(g);
  flip(f, g, u, v, c, d);
  // Both new faces lie across both old ones; their source is the worse one's, so that the
  // input face a face is measured against had no better angle (slivers_left.h): the flip
  // raised the pair's smallest angle above it.
  if (!r_.face_source.empty()) {
    const int worse = r_.face_source[size_t(f_worse ? f : g)];
    r_.face_source[size_t(f)] = r_.face_source[size_t(g)] = worse;
  }
  refile(f);
  refile(g);
  for (int x : {u, v, c, d}) mark_around(x);
  return g;
}

int Collapser::flip_flat_slivers(const std::vector<char>* seed) {
  const double tan_threshold = std::tan(threshold_);
  std::vector<std::pair<int, int>> stack;  // (face, side), face order from the top
  for (int f = int(r_.faces.size()) - 1; f >= 0; --f) {
    if (!alive_[f] || cut_[f]) continue;
    const auto& t = r_.faces[f];
    if (seed && !(*seed)[t[0]] && !(*seed)[t[1]] && !(*seed)[t[2]]) continue;
    if (below_threshold(f, tan_threshold))
      for (int z = 2; z >= 0; --z) stack.push_back({f, z});
  }
  int flips = 0;
  // Each flip raises the mesh's sorted angles, so this ends; the cap guards rounding.
  const long cap = 50L * long(r_.faces.size()) + 1000;
  for (long steps = 0; !stack.empty() && steps < cap; ++steps) {
    const auto [f, z] = stack.back();
    stack.pop_back();
    const int g = flat_flip(f, z);
    if (g < 0) continue;
    ++flips;
    // f = (u, d, c) and g = (d, v, c): the quad's outer sides are f's 0 and 2, g's 0 and 1.
    stack.push_back({g, 1});
    stack.push_back({g, 0});
    stack.push_back({f, 2});
    stack.push_back({f, 0});
  }
  return flips;
}

bool Collapser::stays_near(double pointwise) {
  if (pointwise <= max_dev_) return true;
  near_old_.clear();
  for (int f : replaced_) {
    const auto& t = r_.faces[f];
    near_old_.push_back({P(t[0]), P(t[1]), P(t[2])});
  }
  near_new_.assign(new_pos_.begin(), new_pos_.end());
  return patches_within(near_old_, near_new_, max_dev_);
}

void Collapser::keep_cut_surface() {
  cut_distance_.assign(r_.faces.size(), 0);
  touching_.assign(r_.vertices.size(), 0);
  for (int x = 0; x < int(r_.vertices.size()); ++x) {
    const int others = vertices_at(P(x)) - 1;
    if (others == 0) continue;
    // A neighbour at the same place is the other end of an edge that rounding left without
    // length (its merge was refused, rounded_edges.h): the same sheet, whose needles the
    // step must be free to mend, not a touching one.
    std::vector<int>& ring = scratch_at_v_;
    ring.clear();
    for (int f : vf_[x])
      for (int y : r_.faces[f])
        if (y != x && P(y) == P(x) && std::find(ring.begin(), ring.end(), y) == ring.end()) ring.push_back(y);
    touching_[x] = others > int(ring.size());
  }
}

/// The faces within two rings of a face the cut made: the only ones moves come near.
std::vector<int> faces_near_cut(const Result& r, const std::vector<char>& cut) {
  std::vector<char> in_ring(r.vertices.size(), 0);
  for (int f = 0; f < int(r.faces.size()); ++f)
    if (cut[f])
      for (int x : r.faces[f]) in_ring[x] = 1;
  for (int ring = 0; ring < 2; ++ring) {
    std::vector<char> next = in_ring;
    for (const auto& t : r.faces)
      if (in_ring[t[0]] || in_ring[t[1]] || in_ring[t[2]])
        for (int x : t) next[x] = 1;
    in_ring.swap(next);
  }
  std::vector<int> near_cut;
  for (int f = 0; f < int(r.faces.size()); ++f) {
    const auto& t = r.faces[f];
    if (in_ring[t[0]] || in_ring[t[1]] || in_ring[t[2]]) near_cut.push_back(f);
  }
  return near_cut;
}

bool Collapser::near_cut_surface(double pointwise) {
  double base = 0;
  for (int f : replaced_) base = std::max(base, cut_distance_[f]);
  if (base + pointwise <= max_dev_) {
    move_cut_distance_ = base + pointwise;
    return true;
  }
  // Samples: moved corners, edge quarter points, centroid. A face nearer than the farthest
  // sample so far, or than a quarter of the bound, ends a sample's search: the faces then
  // keep a bound a little above their distance, and small moves later add to it. (So a
  // sample raises `worst` only to its exact distance, whatever face the search tried first.)
  double worst = 0.25 * max_dev_;
  FaceTree::Recent recent;
  auto sample = [&](const V3& p) {
    worst = std::max(worst, cut_surface_.distance(p, worst, max_dev_, &recent));
    return worst <= max_dev_;
  };
  for (size_t i = 0; i < new_pos_.size(); ++i) {
    const auto& q = new_pos_[i];
    const V3 g{(q[0][0] + q[1][0] + q[2][0]) / 3, (q[0][1] + q[1][1] + q[2][1]) / 3, (q[0][2] + q[1][2] + q[2][2]) / 3};
    if (!sample(g)) return false;
    for (int z = 0; z < 3; ++z) {
      const V3& a = q[z];
      const V3& b = q[(z + 1) % 3];
      const int ia = new_ids_[i][z], ib = new_ids_[i][(z + 1) % 3];
      // (A corner that stays where it is is a corner of the old faces, within their bound.)
      // A moved corner and an edge two new faces share are sampled with the first: a point
      // sampled again cannot raise `worst` (some face is within it now).
      bool corner_seen = false;
      for (size_t j = 0; j < i && !corner_seen; ++j) corner_seen = has_corner(new_ids_[j], ia);
      if (!corner_seen && a != P(ia) && !sample(a)) return false;
      bool seen = false;
      for (size_t j = 0; j < i && !seen; ++j)
        seen = has_corner(new_ids_[j], ia) && has_corner(new_ids_[j], ib);
      if (seen) continue;
      for (double t : {0.25, 0.5, 0.75})
        if (!sample({a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])})) return false;
    }
  }
  move_cut_distance_ = worst;
  return true;
}

void Collapser::gather_near_faces() {
  ++new_stamp_;
  for (int f : replaced_) new_mark_[f] = new_stamp_;
  // One lookup for the whole move: the box around all new faces.
  std::vector<std::array<V3, 2>>& boxes = scratch_boxes_;
  boxes.resize(new_ids_.size());
  V3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (size_t i = 0; i < new_ids_.size(); ++i) {
    const V3* q = new_pos_[i].data();
    V3 flo = q[0], fhi = q[0];
    for (int z = 1; z < 3; ++z)
      for (int k = 0; k < 3; ++k) { flo[k] = std::min(flo[k], q[z][k]); fhi[k] = std::max(fhi[k], q[z][k]); }
    boxes[i] = {flo, fhi};
    for (int k = 0; k < 3; ++k) { lo[k] = std::min(lo[k], flo[k]); hi[k] = std::max(hi[k], fhi[k]); }
  }
  grid_.near(lo, hi, near_);
  share_.next.store(0, std::memory_order_relaxed);
  share_.met.store(false, std::memory_order_relaxed);
  share_.cancel.store(false, std::memory_order_relaxed);
}

bool Collapser::meets_new_face(int g) const {
  if (!alive_[g] || new_mark_[g] == new_stamp_) return false;
  // Every pair, also with the star's own ring: a fold at a crease crosses faces
  // that share a corner with the move.
  const auto& t = r_.faces[g];
  const auto& [glo, ghi] = grid_.filed_box(g);  // faces are refiled after every change
  V3 gq[3];
  int kg = -2;  // axis_plane(gq), once a new face is near (gq filled then)
  for (size_t i = 0; i < new_ids_.size(); ++i) {
    if (boxes_apart(glo, ghi, scratch_boxes_[i][0], scratch_boxes_[i][1])) continue;
    if (kg == -2) {
      for (int z = 0; z < 3; ++z) gq[z] = P(t[z]);
      kg = axis_plane(gq);  // CAD plates: most faces nearby lie in such planes
    }
    if (kg >= 0 && meets_axis_plane_only_where_it_was(i, kg, gq[0][kg])) continue;
    if (triangles_meet(new_ids_[i], new_pos_[i].data(), t, gq)) return true;
  }
  return false;
}

void Collapser::test_near_faces() {
  // About eight chunks a move: each claim moves the counter's cache line between the
  // cores, and smaller chunks left this thread waiting for the helper's last one.
  const size_t n = near_.size(), kChunk = std::max<size_t>(2, n / 8);
  for (size_t c; !share_.met.load(std::memory_order_relaxed) && !share_.cancel.load(std::memory_order_relaxed) &&
                 (c = share_.next.fetch_add(kChunk, std::memory_order_relaxed)) < n;)
    for (size_t k = c; k < std::min(n, c + kChunk); ++k)
      if (meets_new_face(near_[k])) {
        share_.met.store(true, std::memory_order_relaxed);
        return;
      }
}

bool Collapser::new_faces_clear() const {
  const auto& boxes = scratch_boxes_;
  for (size_t i = 0; i < new_ids_.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (!boxes_apart(boxes[i][0], boxes[i][1], boxes[j][0], boxes[j][1]) &&
          triangles_meet(new_ids_[i], new_pos_[i].data(), new_ids_[j], new_pos_[j].data()))
        return false;
  return true;
}

bool Collapser::stays_clear() {
  gather_near_faces();
  test_near_faces();
  return !share_.met.load(std::memory_order_relaxed) && new_faces_clear();
}

bool Collapser::near_and_clear(double cut_pointwise, bool compare_patches, double near_pointwise) {
  auto near = [&] { return (!compare_patches || stays_near(near_pointwise)) && near_cut_surface(cut_pointwise); };
  if (!helper_) return near() && stays_clear();
  // The near faces are gathered here; their tests are shared out in chunks, the helper
  // starting on them while this thread takes the deviation checks, then joins it.
  gather_near_faces();
  bool is_near = false;
  helper_->run([&] { test_near_faces(); },
               [&] {
                 is_near = near();
                 if (is_near) test_near_faces();
                 else share_.cancel.store(true, std::memory_order_relaxed);
                 return is_near;
               });
  return is_near && !share_.met.load(std::memory_order_relaxed) && new_faces_clear();
}

bool Collapser::meets_axis_plane_only_where_it_was(size_t i, int k, double c) const {
  const auto& t = new_ids_[i];
  const auto& q = new_pos_[i];
  int on[3], count = 0, above = 0, below = 0;
  for (int z = 0; z < 3; ++z) {
    if (q[z][k] == c) on[count++] = z;
    else if (q[z][k] > c) ++above;
    else ++below;
  }
  if (count == 3 || (above && below)) return false;
  for (int m = 0; m < count; ++m)
    if (!(q[size_t(on[m])] == P(t[size_t(on[m])]))) return false;  // the moved corner
  return count < 2 || edge_exists(t[size_t(on[0])], t[size_t(on[1])]);
}

bool Collapser::cover_unchanged(int gone, int gone2) {
  if (replaced_.empty() || new_ids_.empty()) return false;
  {  // Curved stars leave here: a new face off the plane of the first old one, which is
     // not across a coordinate axis (same_cover would find that out at more cost).
    const auto& t = r_.faces[replaced_[0]];
    const V3 old_face[3] = {P(t[0]), P(t[1]), P(t[2])};
    if (axis_plane(old_face) < 0)
      for (const V3& q : new_pos_[0])
        if (orient3d(old_face[0].data(), old_face[1].data(), old_face[2].data(), q.data()) != 0) return false;
  }
  std::vector<PlacedFace>& before = scratch_before_;
  std::vector<PlacedFace>& after = scratch_after_;
  before.resize(replaced_.size());
  for (size_t n = 0; n < replaced_.size(); ++n) {
    const auto& t = r_.faces[replaced_[n]];
    before[n] = {t, {P(t[0]), P(t[1]), P(t[2])}};
  }
  after.resize(new_ids_.size());
  for (size_t n = 0; n < new_ids_.size(); ++n) after[n] = {new_ids_[n], new_pos_[n]};
  if (!same_cover(before, after)) return false;
  for (int x : {gone, gone2}) {
    if (x < 0) continue;
    const V3 px = P(x);
    if (vertices_at(px) <= 1) continue;  // x alone there
    grid_.near(px, px, scratch_at_v_);
    for (int g : scratch_at_v_)
      if (alive_[g])
        for (int y : r_.faces[g])
          if (y != x && P(y) == px) return false;
  }
  return true;
}

bool Collapser::try_collapse(int v, int w, bool apply, double* dv_out) {
  if (collapse_still_refused(v, w)) return false;
  if (!star_in_slab(v) || !star_in_slab(w)) return false;
  // Every refusal up to the crossing check is remembered (see collapse_still_refused).
  auto refuse = [&] {
    collapse_refused_at_[collapse_key(v, w)] = clock_;
    return false;
  };
  // Lines: v may only slide along its own line edge (v, w) at a vertex of line degree 2, or,
  // where two lines pass closer than a sliver allows (bodies nearly touching on a third one),
  // join a vertex w of the other line: the lines then meet at w. Or bend onto a vertex w
  // of an input crease within the deviation bound: a line running a hair beside a plate's
  // edge (CAD parts that nearly line up, box.STL) leaves a strip that no move inside it
  // can mend. Only at creases: on curved bodies a bent line traps worse slivers later.
  const bool vw_line = line_.count(ekey(v, w)) > 0;
  const bool joins_line = line_degree_[v] == 2 && !vw_line && line_degree_[w] > 0;
  const bool bends_line = line_degree_[v] == 2 && !vw_line && line_degree_[w] == 0 &&
                          norm(sub3(P(v), P(w))) <= max_dev_ && on_crease(w);
  if (line_degree_[v] > 0 && !(vw_line && line_degree_[v] >= 2) && !joins_line && !bends_line) return refuse();
  std::vector<int>& fv = scratch_fv_;
  std::vector<int>& fw = scratch_fw_;
  live_faces(v, fv);
  live_faces(w, fw);
  // Link condition: v and w share exactly the two opposite vertices of their two faces.
  int shared_faces = 0;
  for (int f : fv)
    if (has_corner(r_.faces[f], w)) ++shared_faces;
  if (shared_faces != 2) return refuse();
  std::vector<int>& nv = scratch_nv_;  // one-rings (unique; marked, no sorting)
  std::vector<int>& nw = scratch_nw_;
  nv.clear();
  nw.clear();
  if (ring_mark_.size() != r_.vertices.size()) ring_mark_.assign(r_.vertices.size(), 0);
  const int in_w = ++ring_stamp_, in_v = ++ring_stamp_;
  for (int f : fw)
    for (int x : r_.faces[f])
      if (ring_mark_[x] != in_w) {
        ring_mark_[x] = in_w;
        nw.push_back(x);
      }
  int common = 0;
  for (int f : fv)
    for (int x : r_.faces[f]) {
      if (ring_mark_[x] == in_v) continue;
      if (ring_mark_[x] == in_w && x != v && x != w) ++common;
      ring_mark_[x] = in_v;
      nv.push_back(x);
    }
  if (common != 2) return refuse();
  // Target: w's position, moved along the volume gradient of the new star so that the
  // enclosed volume stays the same (Lindstrom-Turk); the move is tiny where the
  // surface is nearly flat. Coordinates relative to w keep the sums accurate. w stays
  // put when it is on a line other than the one v slides along.
  const bool w_free = line_degree_[w] == 0 || (vw_line && line_degree_[w] == 2);
  const V3 o = P(w);
  auto rel = [&](int x) { return sub3(P(x), o); };
  double s_old = 0;  // six times the old volume of the star (relative to o)
  V3 g{0, 0, 0};     // six times the new volume is g . p (p relative to o)
  for (int pass = 0; pass < 2; ++pass)
    for (int f : pass == 0 ? fv : fw) {
      const auto& t = r_.faces[f];
      const bool has_v = has_corner(t, v);
      const bool has_w = has_corner(t, w);
      if (pass == 1 && has_v) continue;  // counted with v's faces
      s_old += det(rel(t[0]), rel(t[1]), rel(t[2]));
      if (has_v && has_w) continue;  // dies
      for (int z = 0; z < 3; ++z)
        if (t[z] == v || t[z] == w) {
          const V3 bc = cross(rel(t[(z + 1) % 3]), rel(t[(z + 2) % 3]));
          for (int k = 0; k < 3; ++k) g[k] += bc[k];
        }
    }
  const double gg = dot(g, g);
  // Checks one target p (relative to w): no flipped or degenerate face, bounded
  // deviation, a better worst angle; gives six times the volume change.
  auto acceptable = [&](const V3& p, double& dv) {
    if (norm(p) > max_dev_) return false;
    const bool moves_w = p[0] != 0 || p[1] != 0 || p[2] != 0;
    const V3 target{o[0] + p[0], o[1] + p[1], o[2] + p[2]};
    double before = 1e300, after = 1e300;
    int bad_before = 0, bad_after = 0;
    near_old_.clear();
    near_new_.clear();
    for (int pass = 0; pass < 2; ++pass) {
      if (pass == 1 && !moves_w) break;  // w's other faces keep their shape
      for (int f : pass == 0 ? fv : fw) {
        const auto& t = r_.faces[f];
        const bool has_v = has_corner(t, v);
        const bool has_w = has_corner(t, w);
        if (pass == 1 && has_v) continue;
        const double a0 = min_angle(f);
        if (pass == 0) before = std::min(before, a0);
        bad_before += a0 < threshold_;
        near_old_.push_back({P(t[0]), P(t[1]), P(t[2])});
        if (has_v && has_w) continue;
        V3 q[3];
        for (int z = 0; z < 3; ++z) q[z] = t[z] == v || t[z] == w ? target : P(t[z]);
        near_new_.push_back({q[0], q[1], q[2]});
        const V3 n_old = cross(sub3(P(t[1]), P(t[0])), sub3(P(t[2]), P(t[0])));
        const V3 n_new = cross(sub3(q[1], q[0]), sub3(q[2], q[0]));
        const double ln = norm(n_new), lo = norm(n_old);
        if (!(ln > 0) || dot(n_old, n_new) <= 0.1 * lo * ln) return false;
        if (std::fabs(dot(sub3(P(has_v ? v : w), q[0]), n_new)) / ln > max_dev_) return false;
        const double a = smallest_angle(q[0], q[1], q[2]);
        // A face the cut did not make is not turned into a worse sliver (nothing would
        // treat it), but by a bend, which then hands it to the step (below).
        if (!bends_line && !cut_[f] && a < threshold_ && a < a0) return false;
        after = std::min(after, a);
        bad_after += a < threshold_;
      }
    }
    // Better: a larger worst angle, or fewer slivers without making the worst one
    // much worse (two neighbouring slivers often cannot both improve in one step).
    // Not below a degree, though: repeated halvings would ratchet a needle towards zero.
    if (!(after > before || (bad_after < bad_before && after >= 0.5 * before && after >= kNoRatchetBelow)))
      return false;
    // Every point of the star moves at most as far as v (w is within the bound); where v
    // moves further, the faces may still lie near the old ones (a short edge on a smooth
    // star), or not (a star folded over: a fin of rabbit.obj lost 0.045 of its height).
    if (norm(sub3(target, P(v))) > max_dev_ && !patches_within(near_old_, near_new_, max_dev_)) return false;
    dv = dot(g, p) - s_old;
    return true;
  };
  // First the volume-keeping target; if it is refused (a large move on a strongly
  // curved star), w itself, with the volume given back by a neighbour or the budget.
  V3 p{0, 0, 0};
  double dv = 0;
  // The chosen candidate was just weighed in a dry run, with nothing changed since.
  const Weighed* weighed = nullptr;
  if (apply)
    for (const Weighed& c : weighed_)
      if (c.v == v && c.w == w && c.clock == clock_) weighed = &c;
  if (weighed) {
    p = weighed->p;
    dv = weighed->dv;
  } else {
    bool ok = false;
    if (w_free && gg > 0) {
      for (int k = 0; k < 3; ++k) p[k] = s_old / gg * g[k];
      ok = acceptable(p, dv);
    }
    if (!ok) {
      p = {0, 0, 0};
      if (!acceptable(p, dv)) return refuse();
    }
  }
  const V3 target{o[0] + p[0], o[1] + p[1], o[2] + p[2]};
  const bool moved = p[0] != 0 || p[1] != 0 || p[2] != 0;
  if (std::fabs(dv) / 6 > volume_budget_) return refuse();
  // Score: the volume change plus the volume swept by the compensating move.
  if (dv_out) *dv_out = std::fabs(dv) / 6 + norm(p) * std::sqrt(gg) / 6;
  if (!apply) {
    weighed_[next_weighed_++ % weighed_.size()] = {v, w, clock_, p, dv};
    return true;
  }
  // The new star must not run into the rest of the surface (thin plates, nearly
  // touching bodies): checked exactly before anything changes.
  start_move();
  for (int f : fv) {
    const auto& t = r_.faces[f];
    if (has_corner(t, w)) replaced_.push_back(f);  // dies
    else propose(f, v, w, target);
  }
  if (moved)
    for (int f : fw)
      if (!has_corner(r_.faces[f], v)) propose(f, w, w, target);
  if (!proposed_in_slab()) return false;
  if (!cover_unchanged(v, moved ? w : -1)) {
    if (replaces_touching_face() || !near_and_clear(std::max(norm(sub3(target, P(v))), norm(p)))) return false;
    keep_cut_distance();
  }
  const double budget_before = volume_budget_;
  volume_budget_ -= std::fabs(dv) / 6;
  for (int x : nv) changed_[x] = 1;
  for (int x : nw) changed_[x] = 1;
  if (moved) {
    place(w, target);
    for (int f : fw) {
      refile(f);
      if (bends_line) cut_[f] = 1;  // reshaped by the step: treated like the cut's own faces
    }
  }
  const std::vector<int> link = nv;  // copies: compensate() reuses the scratch vectors
  for (int f : fv) {
    auto& t = r_.faces[f];
    if (has_corner(t, w)) {
      touched(f);
      alive_[f] = 0;
      grid_.remove(f);
      continue;
    }
    for (int& x : t)
      if (x == v) x = w;
    vf_[w].push_back(f);
    refile(f);
    if (bends_line) cut_[f] = 1;  // likewise
  }
  vf_[v].clear();
  // Line edges of v now start at w (v's neighbours are the vertices of its old faces).
  if (line_degree_[v] > 0) {
    std::vector<std::pair<int, int>> moved;
    for (int x : nv) {
      if (x == v) continue;
      auto it = line_.find(ekey(v, x));
      if (it == line_.end()) continue;
      if (x != w) moved.push_back(ekey(x, w));
      --line_degree_[v];
      --line_degree_[x];
      line_.erase(it);
    }
    for (const auto& e : moved)
      if (line_.insert(e).second) { ++line_degree_[e.first]; ++line_degree_[e.second]; }
  }
  // w could not take the compensating move: a free neighbour gives the volume back.
  if (!moved && dv != 0)
    for (int x : link)
      if (x != v && x != w && compensate(x, dv)) {
        volume_budget_ = budget_before;
        break;
      }
  return true;
}

bool Collapser::attempt_flip(int f, int z) {
  const int u = r_.faces[f][z], v = r_.faces[f][(z + 1) % 3], c = r_.faces[f][(z + 2) % 3];
  if (line_.count(ekey(u, v)) ) return false;
  const int g = face_across(f, u, v);
  if (g < 0) return false;
  if (!in_slab(f) || !in_slab(g)) {  // (the new faces lie within the two old ones)
    for (int h : {f, g}) for (int y : r_.faces[h]) defer(y);
    return false;
  }
  const int d = third_corner(g, u, v);
  if (edge_exists(c, d)) return false;  // the new edge must not exist already
  const V3 n_f = cross(sub3(P(v), P(u)), sub3(P(c), P(u)));
  const V3 n_g = cross(sub3(P(u), P(v)), sub3(P(d), P(v)));
  const V3 n1 = cross(sub3(P(d), P(u)), sub3(P(c), P(u)));
  const V3 n2 = cross(sub3(P(v), P(d)), sub3(P(c), P(d)));
  for (const V3& n : {n1, n2})
    if (!(norm(n) > 0) || dot(n, n_f) <= 0 || dot(n, n_g) <= 0) return false;
  // How far the surface moves: the distance between the old and the new diagonal.
  const V3 cross_diagonals = cross(sub3(P(v), P(u)), sub3(P(d), P(c)));
  const double lc = norm(cross_diagonals);
  if (!(lc > 0) || std::fabs(dot(sub3(P(c), P(u)), cross(sub3(P(v), P(u)), sub3(P(d), P(u))))) / lc > max_dev_) return false;
  const double before = std::min(min_angle(f), min_angle(g));
  const double after = std::min(smallest_angle(P(u), P(d), P(c)), smallest_angle(P(d), P(v), P(c)));
  if (!(after > before)) return false;
  // (The diagonals' distance bounds the move only where they pass over each other: the
  // two pairs of faces are compared as well, in stays_near.)
  // Six times the volume change, relative to u for accuracy.
  auto rel = [&](int x) { return sub3(P(x), P(u)); };
  const double dv6 = det(rel(u), rel(d), rel(c)) + det(rel(d), rel(v), rel(c)) - det(rel(u), rel(v), rel(c)) -
                     det(rel(v), rel(u), rel(d));
  // Not affordable: some vertex must be able to give the volume back after the flip,
  // planned on the flipped faces (no crossing check) before the flip's own check. 280
  // of box.STL's 1055 flips were checked, applied and undone for want of one.
  size_t first_compensator = 0;
  if (dv6 != 0 && std::fabs(dv6) / 6 > volume_budget_) {
    const FlipUndo undo = flip(f, g, u, v, c, d);
    flip_compensators(u, v, c, d, scratch_compensators_);
    V3 at;
    while (first_compensator < scratch_compensators_.size() &&
           !plan_compensation(scratch_compensators_[first_compensator], dv6, at))
      ++first_compensator;
    unflip(f, g, u, v, c, d, undo);
    if (first_compensator == scratch_compensators_.size()) return false;
  }
  start_move();
  replaced_ = {f, g};
  new_ids_ = {{u, d, c}, {d, v, c}};
  new_pos_ = {{P(u), P(d), P(c)}, {P(d), P(v), P(c)}};
  // A flat convex quad (CAD plates) covers the same place after the flip: nothing to check.
  if (!flat_convex_quad(P(u), P(v), P(c), P(d))) {
    if (replaces_touching_face() || !near_and_clear(1e300, true)) return false;
    keep_cut_distance();
  }
  const FlipUndo undo = flip(f, g, u, v, c, d);
  // Give the volume back by a small move of one free vertex (from the first the plan
  // found: those before it cannot); else it is paid from the budget.
  bool compensated = dv6 == 0;
  if (!compensated) {
    flip_compensators(u, v, c, d, scratch_compensators_);
    for (size_t n = first_compensator; n < scratch_compensators_.size() && !compensated; ++n)
      compensated = compensate(scratch_compensators_[n], dv6);
  }
  if (!compensated) {
    if (std::fabs(dv6) / 6 > volume_budget_) {
      unflip(f, g, u, v, c, d, undo);
      return false;
    }
    volume_budget_ -= std::fabs(dv6) / 6;
  }
  refile(f);
  refile(g);
  cut_[f] = cut_[g] = cut_[f] || cut_[g];  // both new faces replace a cut face: treated on
  for (int x : {u, v, c, d}) mark_around(x);
  return true;
}

bool Collapser::try_junction_slide(int c) {
  if (line_degree_[c] == 0) return false;
  std::vector<int> ring;  // c's line neighbours at junctions (copied: try_collapse reuses scratch)
  std::vector<int>& fc = scratch_fx_;
  live_faces(c, fc);
  for (int f : fc)
    for (int j : r_.faces[f])
      if (j != c && line_degree_[j] >= 3 && line_.count(ekey(c, j)) &&
          std::find(ring.begin(), ring.end(), j) == ring.end())
        ring.push_back(j);
  for (int j : ring)
    if (try_collapse(j, c)) return true;
  return false;
}

bool Collapser::attempt_removal(int v) {
  const int ld = line_degree_[v];
  if (ld != 0 && ld != 2) return false;
  if (!star_in_slab(v)) return false;  // (the new faces lie within the old star)
  // Scratch members: this runs for every sliver corner, pass after pass.
  std::vector<int>& fv = removal_faces_;
  live_faces(v, fv);
  const int k = int(fv.size());
  if (k < 3 || k > kMaxRemovedValence) return false;
  // The link in order: each face (v, a, b) gives the link side a -> b.
  std::vector<std::array<int, 2>>& sides = removal_sides_;
  sides.clear();
  for (int f : fv) {
    const auto& t = r_.faces[f];
    for (int z = 0; z < 3; ++z)
      if (t[z] == v) sides.push_back({t[(z + 1) % 3], t[(z + 2) % 3]});
  }
  std::vector<int>& ring = removal_ring_;
  ring.assign(1, sides[0][0]);
  for (int step = 0; step < k; ++step) {
    int next = -1;
    for (const auto& sd : sides)
      if (sd[0] == ring.back()) next = next < 0 ? sd[1] : -2;
    if (next < 0) return false;  // not a single closed fan
    if (step + 1 < k) {
      if (std::find(ring.begin(), ring.end(), next) != ring.end()) return false;
      ring.push_back(next);
    } else if (next != ring[0]) {
      return false;
    }
  }
  std::array<int, 2> forced{-1, -1};
  if (ld == 2) {
    int n = 0;
    for (int i = 0; i < k; ++i)
      if (line_.count(ekey(v, ring[i]))) forced[n++] = i;
    if (n != 2 || line_.count(ekey(ring[forced[0]], ring[forced[1]]))) return false;
    // The line's new edge is kept without the link triangulation's test that a diagonal is
    // not an edge already (elsewhere in the surface: it would get four faces).
    const int gap = forced[1] - forced[0];
    if (gap != 1 && gap != k - 1 && edge_exists(ring[forced[0]], ring[forced[1]])) return false;
  }
  // (The link triangulation below is the expensive part of a refusal.)
  if (star_unchanged_since(removal_refused_at_[v], v, fv)) return false;
  auto refuse = [&] {
    removal_refused_at_[v] = clock_;
    return false;
  };
  V3 up{0, 0, 0};
  for (int f : fv) {
    const auto& t = r_.faces[f];
    const V3 n = cross(sub3(P(t[1]), P(t[0])), sub3(P(t[2]), P(t[0])));
    for (int c = 0; c < 3; ++c) up[c] += n[c];
  }
  std::vector<V3>& at = removal_at_;
  at.resize(size_t(k));
  for (int i = 0; i < k; ++i) at[i] = P(ring[i]);
  double before = 1e300;
  bool any_cut = false;
  for (int f : fv) {
    before = std::min(before, min_angle(f));
    any_cut |= cut_[f] != 0;
  }
  std::vector<std::array<int, 3>>& tris = removal_tris_;
  tris.clear();
  double after = 0;
  if (!best_polygon_triangulation(
          at, up, [&](int i, int j) { return !edge_exists(ring[i], ring[j]); }, forced, tris, after, before))
    return refuse();
  if (!any_cut && after < threshold_) return refuse();
  // Each new face faces the way of the star and passes within the deviation bound of v.
  const V3 pv = P(v);
  double dv6 = 0;  // six times the volume change (the old faces span nothing seen from v)
  for (const auto& t : tris) {
    const V3 a = sub3(at[t[0]], pv), b = sub3(at[t[1]], pv), c = sub3(at[t[2]], pv);
    const V3 n = cross(sub3(b, a), sub3(c, a));
    const double ln = norm(n);
    if (!(ln > 0) || dot(n, up) <= 0.1 * ln * norm(up)) return refuse();
    if (std::fabs(dot(a, n)) / ln > max_dev_) return refuse();
    dv6 += det(a, b, c);
  }
  if (std::fabs(dv6) / 6 > volume_budget_) return refuse();
  start_move();
  replaced_ = fv;
  for (const auto& t : tris) {
    new_ids_.push_back({ring[t[0]], ring[t[1]], ring[t[2]]});
    new_pos_.push_back({at[t[0]], at[t[1]], at[t[2]]});
  }
  if (!cover_unchanged(v)) {
    if (replaces_touching_face() || !stays_near()) return refuse();
    if (!near_and_clear(1e300)) return false;
    keep_cut_distance();
  }
  // Each new face's source: the old face at one of its corners that is not an end of the
  // line through v (faces at such a corner lie on its side of the line, the same body's).
  std::vector<int>& sources = removal_sources_;
  sources.clear();
  if (!r_.face_source.empty())
    for (const auto& t : tris) {
      int c = t[0];
      for (int z : t)
        if (z != forced[0] && z != forced[1]) { c = z; break; }
      for (int j = 0; j < k; ++j)
        if (sides[size_t(j)][0] == ring[size_t(c)]) { sources.push_back(r_.face_source[size_t(fv[size_t(j)])]); break; }
    }
  // The first k - 2 faces of the star take the new triangles; the last two go.
  for (int x : ring) {
    auto& list = vf_[x];
    list.erase(std::remove_if(list.begin(), list.end(),
                              [&](int f) { return std::find(fv.begin(), fv.end(), f) != fv.end(); }),
               list.end());
  }
  vf_[v].clear();
  for (int i = 0; i < k; ++i) {
    const int f = fv[i];
    if (i < k - 2) {
      r_.faces[f] = new_ids_[size_t(i)];
      if (!sources.empty()) r_.face_source[size_t(f)] = sources[size_t(i)];
      cut_[f] = any_cut;
      for (int x : r_.faces[f]) vf_[x].push_back(f);
      refile(f);
    } else {
      touched(f);
      alive_[f] = 0;
      grid_.remove(f);
    }
  }
  if (ld == 2) {
    const int a = ring[forced[0]], b = ring[forced[1]];
    line_.erase(ekey(v, a));
    line_.erase(ekey(v, b));
    line_degree_[v] = 0;
    line_.insert(ekey(a, b));  // the line's other edges at a and b stay: degrees unchanged
  }
  for (int x : ring) mark_around(x);
  const double budget_before = volume_budget_;
  volume_budget_ -= std::fabs(dv6) / 6;
  if (dv6 != 0)
    for (int x : ring)
      if (compensate(x, dv6)) {
        volume_budget_ = budget_before;
        break;
      }
  return true;
}

bool Collapser::attempt_slide_on_line(int x) {
  if (line_degree_[x] != 2 || !star_in_slab(x)) return false;
  std::vector<int>& fx = slide_faces_;  // (scratch: tried for every line vertex, pass after pass)
  live_faces(x, fx);
  if (star_unchanged_since(slide_refused_at_[x], x, fx)) return false;
  // Every refusal up to the crossing check is remembered (see star_unchanged_since).
  auto refuse = [&] {
    slide_refused_at_[x] = clock_;
    return false;
  };
  int ends[2], n = 0;
  for (int f : fx)
    for (int y : r_.faces[f])
      if (y != x && n < 2 && line_.count(ekey(x, y)) && (n == 0 || ends[0] != y)) ends[n++] = y;
  if (n != 2) return refuse();
  double before = 1e300;
  for (int f : fx) before = std::min(before, min_angle(f));
  const V3 o = P(x);
  V3 best_at = o;
  double best = before;
  for (int e = 0; e < 2; ++e) {
    const V3 d = sub3(P(ends[e]), o);
    for (double t : {0.15, 0.3, 0.5, 0.7}) {
      const V3 at{o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
      // The line now runs straight from the other neighbour to `at`: it leaves the
      // intersection curve by at most the distance of x from that chord.
      const V3 chord = sub3(at, P(ends[1 - e]));
      const V3 off = cross(sub3(o, P(ends[1 - e])), chord);
      if (!(norm(chord) > 0) || norm(off) / norm(chord) > max_dev_) continue;
      double worst = 1e300;
      bool fine = true;
      for (int f : fx) {
        V3 q[3];
        if (!moved_face(f, x, at, q)) { fine = false; break; }
        const double a = smallest_angle(q[0], q[1], q[2]);
        // A face no better than the best place so far: this place cannot win.
        if ((!cut_[f] && a < threshold_ && a < min_angle(f)) || !(a > best)) { fine = false; break; }
        worst = std::min(worst, a);
      }
      if (fine && worst > best) { best = worst; best_at = at; }
    }
  }
  if (!(best > before * (1 + kMinSlideGain))) return refuse();
  // Six times the volume change of the move, given back by a free neighbour or paid.
  double dv6 = 0;
  for (int f : fx) {
    const auto& t = r_.faces[f];
    V3 q[3];
    for (int z = 0; z < 3; ++z) q[z] = t[z] == x ? best_at : P(t[z]);
    dv6 += det(sub3(q[0], o), sub3(q[1], o), sub3(q[2], o));  // old faces span nothing seen from o
  }
  std::vector<int>& ring = slide_ring_;  // free neighbours, which may give the volume back
  ring.clear();
  for (int f : fx)
    for (int y : r_.faces[f])
      if (y != x && line_degree_[y] == 0 && std::find(ring.begin(), ring.end(), y) == ring.end()) ring.push_back(y);
  const bool affordable = std::fabs(dv6) / 6 <= volume_budget_;
  if (!affordable) {
    // Some free neighbour must be able to give the volume back after the move: planned
    // with x moved (no crossing check yet), before anything is checked exactly.
    place(x, best_at);
    bool plan = false;
    V3 at;
    for (int y : ring)
      if (!plan) plan = plan_compensation(y, dv6, at);
    place(x, o);
    if (!plan) return refuse();
  }
  std::vector<std::pair<int, char>>& marks = slide_marks_;  // changed_ before the move, restored if undone
  marks.clear();
  for (int f : fx)
    for (int y : r_.faces[f]) marks.push_back({y, changed_[y]});
  if (!move_vertex(x, fx, best_at)) return false;
  if (dv6 == 0) return true;
  for (int y : ring)
    if (compensate(y, dv6)) return true;
  if (affordable) {
    volume_budget_ -= std::fabs(dv6) / 6;
    return true;
  }
  // Neither given back nor affordable: x goes back where it was (which was clear), and
  // nothing counts as changed.
  place(x, o);
  for (int f : fx) refile(f);
  for (auto it = marks.rbegin(); it != marks.rend(); ++it) changed_[it->first] = it->second;
  return false;
}

bool Collapser::attempt_relocation(int x) {
  if (line_degree_[x] > 0 || !star_in_slab(x)) return false;
  std::vector<int>& fx = scratch_fx_;
  live_faces(x, fx);
  if (fx.empty()) return false;
  const V3 o = P(x);
  V3 g{0, 0, 0}, centroid{0, 0, 0};
  for (int f : fx) {
    const auto& t = r_.faces[f];
    for (int z = 0; z < 3; ++z)
      if (t[z] == x) {
        const V3 b = sub3(P(t[(z + 1) % 3]), o), c = sub3(P(t[(z + 2) % 3]), o);
        const V3 bc = cross(b, c);
        for (int k = 0; k < 3; ++k) {
          g[k] += bc[k];
          centroid[k] += (b[k] + c[k]) / (2.0 * double(fx.size()));
        }
      }
  }
  const double gg = dot(g, g);
  if (!(gg > 0)) return false;
  // Only on a smooth patch (no crease through x): there the slide barely moves the surface.
  for (int f : fx) {
    const auto& t = r_.faces[f];
    const V3 n = cross(sub3(P(t[1]), P(t[0])), sub3(P(t[2]), P(t[0])));
    if (dot(n, g) < kSmoothStarCos * norm(n) * std::sqrt(gg)) return false;
  }
  V3 delta = centroid;
  const double along = dot(g, delta) / gg;
  for (int k = 0; k < 3; ++k) delta[k] -= along * g[k];  // g . delta = 0: same volume
  const double len = norm(delta);
  if (!(len > 0)) return false;
  if (len > max_dev_)
    for (double& d : delta) d *= max_dev_ / len;
  const V3 moved{o[0] + delta[0], o[1] + delta[1], o[2] + delta[2]};
  double before = 1e300, after = 1e300;
  for (int f : fx) {
    V3 q[3];
    if (!moved_face(f, x, moved, q)) return false;
    const double a = smallest_angle(q[0], q[1], q[2]);
    if (!cut_[f] && a < threshold_ && a < min_angle(f)) return false;
    before = std::min(before, min_angle(f));
    after = std::min(after, a);
  }
  if (!(after > before)) return false;
  return move_vertex(x, fx, moved);
}

bool Collapser::move_vertex(int x, const std::vector<int>& fx, const V3& at) {
  start_move();
  for (int f : fx) propose(f, x, x, at);
  if (!proposed_in_slab()) return false;
  // Every point of the faces moves at most as far as x (a slide along a line may move
  // further than the bound: then the patches are compared, unless they cover the same).
  if (!cover_unchanged(x)) {
    const double moved = norm(sub3(at, P(x)));
    if (replaces_touching_face() || !near_and_clear(moved, true, moved)) return false;
    keep_cut_distance();
  }
  place(x, at);
  for (int f : fx) {
    refile(f);
    for (int y : r_.faces[f]) changed_[y] = 1;
  }
  return true;
}

bool Collapser::plan_compensation(int x, double dv6, V3& moved) {
  if (line_degree_[x] > 0 || !star_in_slab(x)) return false;
  std::vector<int>& fx = scratch_fx_;
  live_faces(x, fx);
  const V3 o = P(x);
  V3 g{0, 0, 0};  // six times the volume change is g . delta
  for (int f : fx) {
    const auto& t = r_.faces[f];
    for (int z = 0; z < 3; ++z)
      if (t[z] == x) {
        const V3 bc = cross(sub3(P(t[(z + 1) % 3]), o), sub3(P(t[(z + 2) % 3]), o));
        for (int k = 0; k < 3; ++k) g[k] += bc[k];
      }
  }
  const double gg = dot(g, g);
  if (!(gg > 0)) return false;
  V3 delta;
  for (int k = 0; k < 3; ++k) delta[k] = -dv6 / gg * g[k];
  if (norm(delta) > max_dev_) return false;
  moved = {o[0] + delta[0], o[1] + delta[1], o[2] + delta[2]};
  for (int f : fx) {
    V3 q[3];
    if (!moved_face(f, x, moved, q)) return false;
    if (smallest_angle(q[0], q[1], q[2]) < std::min(min_angle(f), threshold_)) return false;
  }
  return true;
}

bool Collapser::compensate(int x, double dv6) {
  V3 moved;
  return plan_compensation(x, dv6, moved) && move_vertex(x, scratch_fx_, moved);
}

int Collapser::run(double threshold, const std::vector<char>* seed, const std::vector<double>* cut_distance) {
  threshold_ = threshold;
  // Two rounds: first only moves that give the volume back (a budget of rounding), so
  // the budget is not spent on the worst slivers while cheaper fixes exist; then the rest.
  const double budget = volume_budget_;
  const double rounding = std::min(budget, 1e-12 * budget_scale_);
  changed_at_.assign(r_.vertices.size(), 0);
  keep_cut_surface();
  if (cut_distance) cut_distance_ = *cut_distance;
  flip_refused_now_.assign(3 * r_.faces.size(), -1);
  removal_refused_now_.assign(r_.vertices.size(), -1);
  slide_refused_now_.assign(r_.vertices.size(), -1);
  relocation_refused_now_.assign(r_.vertices.size(), -1);
  // The flat flips first; the vertices of the faces they changed join the seed.
  std::vector<char> flat_seed;
  changed_.assign(r_.vertices.size(), 0);
  flat_flips_ = flip_flat_slivers(seed);
  if (seed && flat_flips_ > 0) {
    flat_seed = *seed;
    for (size_t x = 0; x < flat_seed.size(); ++x) flat_seed[x] = flat_seed[x] || changed_[x];
    seed = &flat_seed;
  }
  for (int round = 0; round < 2; ++round) {
    ++clock_;
    removal_refused_at_.assign(r_.vertices.size(), -1);
    slide_refused_at_.assign(r_.vertices.size(), -1);
    collapse_refused_at_.clear();
    if (round == 0) volume_budget_ = rounding;
    else volume_budget_ = budget - (rounding - volume_budget_);
    run_passes(threshold, seed);
  }
  return collapses_;
}

double Collapser::hand_over(std::vector<char>& alive, std::vector<char>& cut, std::vector<double>& cut_distance,
                            std::vector<char>& deferred) {
  for (int f = 0; f < int(r_.faces.size()); ++f)
    for (int z = 0; z < 3; ++z) r_.line_edge[f][z] = alive_[f] && line_.count(ekey(r_.faces[f][z], r_.faces[f][(z + 1) % 3])) > 0;
  alive = alive_;
  cut = cut_;
  cut_distance = cut_distance_;
  deferred = deferred_.empty() ? std::vector<char>(r_.vertices.size(), 0) : deferred_;
  return volume_budget_;
}

void Collapser::run_passes(double threshold, const std::vector<char>* seed) {
  if (seed) changed_ = *seed;
  else changed_.assign(r_.vertices.size(), 1);
  for (int pass = 0; pass < 10; ++pass) {
    // After the first pass only slivers whose neighbourhood changed can have new options.
    std::vector<char> changed;
    changed.swap(changed_);
    changed_.assign(r_.vertices.size(), 0);
    std::vector<std::pair<double, int>> bad;
    for (int f = 0; f < int(r_.faces.size()); ++f)
      if (alive_[f] && cut_[f]) {
        const auto& t = r_.faces[f];
        if ((pass > 0 || seed) && !changed[t[0]] && !changed[t[1]] && !changed[t[2]]) continue;
        const double a = min_angle(f);
        if (a < threshold) bad.push_back({a, f});
      }
    std::sort(bad.begin(), bad.end());
    int done = 0;
    for (const auto& [a0, f] : bad) {
      if (!alive_[f] || min_angle(f) >= threshold) continue;
      const auto t = r_.faces[f];
      if ((pass > 0 || seed) && !changed[t[0]] && !changed[t[1]] && !changed[t[2]]) continue;
      // Edges by length, shortest first; each tried in both directions. A cap (one
      // large angle) is first flipped across its longest edge, which moves nothing.
      std::array<std::pair<double, int>, 3> edges;
      for (int z = 0; z < 3; ++z) edges[z] = {norm(sub3(P(t[z]), P(t[(z + 1) % 3]))), z};
      std::sort(edges.begin(), edges.end());
      const bool cap = corner_angle(P(t[(edges[2].second + 2) % 3]), P(t[edges[2].second]), P(t[(edges[2].second + 1) % 3])) >
                       2 * kPi / 3;
      if (cap && try_flip(f, edges[2].second)) { ++done; ++flips_; continue; }
      // Of the allowed collapses, the one that changes the volume least.
      bool ok = false;
      int best_v = -1, best_w = -1;
      double best_dv = 1e300;
      // (A collapse that changes and sweeps no volume, flat stars on CAD plates, cannot be
      // beaten: the rest are not evaluated.)
      for (int e = 0; e < 3 && best_dv > 0; ++e)
        for (int dir = 0; dir < 2 && best_dv > 0; ++dir) {
          const int z = edges[e].second;
          const int a = t[(z + dir) % 3], b = t[(z + 1 - dir) % 3];
          double dv = 0;
          if (try_collapse(a, b, false, &dv) && dv < best_dv) { best_dv = dv; best_v = a; best_w = b; }
        }
      if (best_v >= 0 && try_collapse(best_v, best_w)) { ++done; ++collapses_; ok = true; }
      // Or an end of the short edge (then the third corner) leaves, its star filled again.
      for (int c : {t[edges[0].second], t[(edges[0].second + 1) % 3], t[(edges[0].second + 2) % 3]})
        if (!ok && try_remove_vertex(c)) { ++done; ++collapses_; ok = true; }
      // Otherwise a flip of any side may reshape the neighbourhood for a later pass.
      for (int k = 2; k >= 0 && !ok; --k)
        if (try_flip(f, edges[k].second)) { ++done; ++flips_; ok = true; }
      for (int z = 0; z < 3 && !ok; ++z)
        if (try_junction_slide(t[z])) { ++done; ++collapses_; ok = true; }
      // Or a corner slides towards the middle of its ring, within the surface.
      for (int z = 0; z < 3 && !ok; ++z)
        if (try_relocate(t[z])) { ++done; ok = true; }
      for (int z = 0; z < 3 && !ok; ++z)
        if (try_slide_on_line(t[z])) { ++done; ok = true; }
    }
    if (done == 0) break;
  }
}

void Collapser::compact() {
  std::vector<int> index(r_.vertices.size(), -1);
  std::vector<V3> vertices;
  std::vector<std::array<int, 3>> faces;
  for (int f = 0; f < int(r_.faces.size()); ++f) {
    if (!alive_[f]) continue;
    std::array<int, 3> t;
    for (int z = 0; z < 3; ++z) {
      const int v = r_.faces[f][z];
      if (index[v] < 0) { index[v] = int(vertices.size()); vertices.push_back(r_.vertices[v]); }
      t[z] = index[v];
    }
    faces.push_back(t);
  }
  std::vector<std::array<bool, 3>> line(faces.size());
  size_t k = 0;
  const bool sources = !r_.face_source.empty();
  for (int f = 0; f < int(r_.faces.size()); ++f) {
    if (!alive_[f]) continue;
    for (int z = 0; z < 3; ++z) line[k][z] = line_.count(ekey(r_.faces[f][z], r_.faces[f][(z + 1) % 3])) > 0;
    if (sources) r_.face_source[k] = r_.face_source[size_t(f)];
    ++k;
  }
  if (sources) r_.face_source.resize(k);
  r_.vertices = std::move(vertices);
  r_.faces = std::move(faces);
  r_.line_edge = std::move(line);
}

}  // namespace

double min_angle_deg(const std::vector<std::array<double, 3>>& v, const std::vector<std::array<int, 3>>& f) {
  double best = 180;
  for (const auto& t : f) best = std::min(best, smallest_angle(v[t[0]], v[t[1]], v[t[2]]) * 180 / kPi);
  return best;
}

namespace {

// Below this many slivers one collapser treats the whole surface: the parts' setup and
// the run along their border would cost more than the second thread saves.
constexpr size_t kMinSliversForParts = 4000;

Limits limits_of(const Result& r, double max_deviation, double max_volume_change) {
  // About a vertex of the surface, not the origin (far from it the terms cancel to noise).
  double volume = 0;
  const V3 o = r.faces.empty() ? V3{0, 0, 0} : r.vertices[size_t(r.faces[0][0])];
  for (const auto& t : r.faces)
    volume += dot(sub3(r.vertices[t[0]], o), cross(sub3(r.vertices[t[1]], o), sub3(r.vertices[t[2]], o))) / 6;
  V3 lo = r.vertices.empty() ? V3{0, 0, 0} : r.vertices[0], hi = lo;
  for (const auto& p : r.vertices)
    for (int k = 0; k < 3; ++k) { lo[k] = std::min(lo[k], p[k]); hi[k] = std::max(hi[k], p[k]); }
  return {max_deviation * norm(sub3(hi, lo)), max_volume_change * std::fabs(volume), std::fabs(volume)};
}

/// A slab's faces and every face reaching into it, with the vertices they use, and
/// what its collapser left.
struct Part {
  Slab slab;
  Result r;
  std::vector<char> cut;
  std::vector<int> face_of, vertex_of;  // local index -> the whole surface's
  std::vector<char> alive, deferred;
  std::vector<double> cut_distance;
  double budget_left = 0;
  int moves = 0, flat_flips = 0;
};

bool reaches_into(const Result& r, int f, const Slab& s) {
  double mn = HUGE_VAL, mx = -HUGE_VAL;
  for (int x : r.faces[f]) {
    mn = std::min(mn, r.vertices[x][s.axis]);
    mx = std::max(mx, r.vertices[x][s.axis]);
  }
  return mn < s.hi && mx > s.lo;
}

void extract(const Result& r, const std::vector<char>& cut, Part& p) {
  std::vector<int> local(r.vertices.size(), -1);
  for (int f = 0; f < int(r.faces.size()); ++f) {
    if (!reaches_into(r, f, p.slab)) continue;
    std::array<int, 3> t;
    for (int z = 0; z < 3; ++z) {
      int& l = local[r.faces[f][z]];
      if (l < 0) {
        l = int(p.vertex_of.size());
        p.vertex_of.push_back(r.faces[f][z]);
        p.r.vertices.push_back(r.vertices[r.faces[f][z]]);
      }
      t[z] = l;
    }
    p.face_of.push_back(f);
    p.r.faces.push_back(t);
    p.r.line_edge.push_back(r.line_edge[f]);
    if (!r.face_source.empty()) p.r.face_source.push_back(r.face_source[f]);
    p.cut.push_back(cut[f]);
  }
}

/// Runs a collapser in part p's slab. `seed` (per vertex) and `cut_distance` (per face)
/// are the whole surface's, or null.
void run_part(Part& p, const Limits& limits, double threshold, const CutSurface& cut_surface,
              const std::vector<char>* seed, const std::vector<double>* cut_distance) {
  std::vector<char> local_seed;
  std::vector<double> local_distance;
  if (seed)
    for (int v : p.vertex_of) local_seed.push_back((*seed)[size_t(v)]);
  if (cut_distance)
    for (int f : p.face_of) local_distance.push_back((*cut_distance)[size_t(f)]);
  Collapser c(p.r, p.cut, limits, nullptr, cut_surface, p.slab);
  p.moves = c.run(threshold, seed ? &local_seed : nullptr, cut_distance ? &local_distance : nullptr);
  p.flat_flips = c.flat_flips_;
  p.budget_left = c.hand_over(p.alive, p.cut, p.cut_distance, p.deferred);
}

/// Writes the parts' changes back into r: a part changes only faces inside its slab, and
/// the slabs are apart, so no face or vertex is changed by two. Dead faces go (vertices
/// stay, some then unused). `seed` gets the vertices of faces in more than one part (on
/// the slabs' border) and those whose moves a slab refused.
void apply_parts(Result& r, std::vector<char>& cut, std::vector<double>& cut_distance, std::vector<char>& seed,
                 const std::vector<Part*>& parts) {
  const size_t nf = r.faces.size();
  std::vector<int> owner(nf, -1), local_face(nf, -1);  // owner -2: in several parts
  for (size_t i = 0; i < parts.size(); ++i)
    for (size_t l = 0; l < parts[i]->face_of.size(); ++l) {
      const int f = parts[i]->face_of[l];
      owner[f] = owner[f] == -1 ? int(i) : -2;
      local_face[f] = int(l);
    }
  for (const Part* p : parts)
    for (size_t l = 0; l < p->vertex_of.size(); ++l) r.vertices[size_t(p->vertex_of[l])] = p->r.vertices[l];
  seed.assign(r.vertices.size(), 0);
  size_t k = 0;
  const bool sources = !r.face_source.empty();
  for (size_t f = 0; f < nf; ++f) {
    const int i = owner[f];
    if (i >= 0) {
      const Part& p = *parts[size_t(i)];
      const size_t l = size_t(local_face[f]);
      if (!p.alive[l]) continue;
      for (int z = 0; z < 3; ++z) r.faces[k][z] = p.vertex_of[size_t(p.r.faces[l][z])];
      r.line_edge[k] = p.r.line_edge[l];
      cut[k] = p.cut[l];
      cut_distance[k] = p.cut_distance[l];
      if (sources) r.face_source[k] = p.r.face_source[l];
    } else {
      if (i == -2)
        for (int x : r.faces[f]) seed[size_t(x)] = 1;
      r.faces[k] = r.faces[f];
      r.line_edge[k] = r.line_edge[f];
      cut[k] = cut[f];
      cut_distance[k] = cut_distance[f];
      if (sources) r.face_source[k] = r.face_source[f];
    }
    ++k;
  }
  r.faces.resize(k);
  r.line_edge.resize(k);
  cut.resize(k);
  cut_distance.resize(k);
  if (sources) r.face_source.resize(k);
  for (const Part* p : parts)
    for (size_t l = 0; l < p->vertex_of.size(); ++l)
      if (p->deferred[l]) seed[size_t(p->vertex_of[l])] = 1;
}

/// The slivers' median along the longest extent of their centroids: two slabs, each
/// with about half of them.
std::array<Slab, 2> halves(const Result& r, const std::vector<int>& slivers) {
  V3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  std::vector<V3> centroid(slivers.size());
  for (size_t i = 0; i < slivers.size(); ++i) {
    const auto& t = r.faces[slivers[i]];
    for (int k = 0; k < 3; ++k) {
      centroid[i][k] = (r.vertices[t[0]][k] + r.vertices[t[1]][k] + r.vertices[t[2]][k]) / 3;
      lo[k] = std::min(lo[k], centroid[i][k]);
      hi[k] = std::max(hi[k], centroid[i][k]);
    }
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (hi[k] - lo[k] > hi[axis] - lo[axis]) axis = k;
  std::vector<double> c(slivers.size());
  for (size_t i = 0; i < c.size(); ++i) c[i] = centroid[i][axis];
  std::nth_element(c.begin(), c.begin() + ptrdiff_t(c.size() / 2), c.end());
  const double m = c[c.size() / 2];
  return {Slab{axis, -HUGE_VAL, m}, Slab{axis, m, HUGE_VAL}};
}

int collapse_in_halves(Result& r, const std::vector<char>& cut_in, const Limits& limits, double threshold,
                       const std::vector<int>& slivers, SideWorker* helper, int* flat_flips) {
  const std::array<Slab, 2> slabs = halves(r, slivers);
  std::array<Part, 2> halves_run;
  std::array<FaceTree, 2> trees;  // each half's part of the cut's surface, as the cut left it
  Limits half = limits;
  half.volume_budget /= 2;
  parallel_for(2, 1, [&](size_t i) {
    Part& p = halves_run[i];
    p.slab = slabs[i];
    extract(r, cut_in, p);
    trees[i] = FaceTree(p.r.vertices, p.r.faces, faces_near_cut(p.r, p.cut));
    run_part(p, half, threshold, CutSurface{&trees[i]}, nullptr, nullptr);
  });
  std::vector<char> cut = cut_in, seed;
  std::vector<double> cut_distance(r.faces.size(), 0);
  apply_parts(r, cut, cut_distance, seed, {&halves_run[0], &halves_run[1]});
  // Then the whole surface, for the slivers either half left: those on the border and
  // any a half could not mend alone (its share of the budget spent, or a move it had to
  // refuse), with the budget the halves left.
  for (size_t f = 0; f < r.faces.size(); ++f) {
    const auto& t = r.faces[f];
    if (cut[f] && smallest_angle(r.vertices[t[0]], r.vertices[t[1]], r.vertices[t[2]]) < threshold)
      for (int x : t) seed[size_t(x)] = 1;
  }
  Limits rest = limits;
  for (const Part& p : halves_run) rest.volume_budget -= half.volume_budget - p.budget_left;
  rest.volume_budget = std::max(0.0, rest.volume_budget);
  Collapser c(r, cut, rest, helper, CutSurface{&trees[0], &trees[1]});
  const int moves = halves_run[0].moves + halves_run[1].moves + c.run(threshold, &seed, &cut_distance);
  if (flat_flips) *flat_flips = halves_run[0].flat_flips + halves_run[1].flat_flips + c.flat_flips_;
  c.compact();
  return moves;
}

}  // namespace

int collapse_slivers(Result& r, const std::vector<char>& cut, double sliver_angle_deg, double max_deviation,
                     double max_volume_change, SideWorker* helper, int* parts, int* flat_flips) {
  const double threshold = sliver_angle_deg * kPi / 180;
  const Limits limits = limits_of(r, max_deviation, max_volume_change);
  std::vector<int> slivers;
  for (int f = 0; f < int(r.faces.size()); ++f) {
    const auto& t = r.faces[f];
    if (cut[f] && smallest_angle(r.vertices[t[0]], r.vertices[t[1]], r.vertices[t[2]]) < threshold) slivers.push_back(f);
  }
  // Many slivers: two halves of the surface at once (the same result on one thread).
  if (slivers.size() >= kMinSliversForParts) {
    if (parts) *parts = 2;
    return collapse_in_halves(r, cut, limits, threshold, slivers, helper, flat_flips);
  }
  if (parts) *parts = 1;
  // The tree and the collapser's own tables both only read r.
  FaceTree tree;
  std::optional<Collapser> c;
  auto build_tree = [&] { tree = FaceTree(r.vertices, r.faces, faces_near_cut(r, cut)); };
  auto set_up = [&] {
    c.emplace(r, cut, limits, helper, CutSurface{&tree});
    return true;
  };
  if (helper) {
    helper->run(build_tree, set_up);
  } else {
    build_tree();
    set_up();
  }
  const int n = c->run(threshold);
  if (flat_flips) *flat_flips = c->flat_flips_;
  c->compact();
  return n;
}

}  // namespace mr::surface_union
