// The sliver step's collapser: the state of one run over the surface (or over a slab of
// it), its moves and their checks. Internal to the union core; sliver_collapse.h is the
// interface. The moves are defined by kind: sliver_flips.cpp, sliver_edge_collapse.cpp,
// sliver_vertex_moves.cpp; their exact and deviation checks in sliver_move_checks.cpp; the
// passes over the slivers in sliver_passes.cpp.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "common/flat_index_map.h"
#include "common/side_worker.h"
#include "union/face_clearance.h"
#include "union/face_tree.h"
#include "union/patch_distance.h"
#include "union/same_cover.h"
#include "union/surface_union.h"
#include "union/triangle_angles.h"
#include "union/vec3.h"

namespace mr::surface_union::slivers {

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
// A move that mends a face under this angle may fold the surface in any round (folds_more):
// needles between nearly coincident sheets (a CAD part and a copy turned by a rounded half
// turn) kept a tenth of a degree when they waited for the last round.
constexpr double kMayFoldBelow = kPi / 180;
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
  /// `beat` (dry runs): a score the collapse must beat to matter; one that cannot is refused
  /// without being weighed.
  bool try_collapse(int v, int w, bool apply = true, double* dv_out = nullptr, double beat = HUGE_VAL);
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
    renamed_from_ = renamed_to_ = -1;
    new_line_edge_ = {-1, -1};
  }
  /// Face f with corner `from` replaced by `to` at position `at` (from == to: a move).
  void propose(int f, int from, int to, const V3& at) {
    replaced_.push_back(f);
    if (from != to) { renamed_from_ = from; renamed_to_ = to; }
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
  /// The proposed faces fold the surface where it was not folded: two faces meeting at an
  /// edge off the lines (among the new faces, or a new face and an old neighbour) turn by
  /// more than a crease angle, where no two at the replaced faces' sides did, and no
  /// replaced face is under kMayFoldBelow. Such moves wait for the last round
  /// (allow_folds_), which starts at their corners: repeated small moves of a curved star
  /// (relocations, collapses beside a line) left folds there that a regrid keeping the
  /// lines takes for ridges, with narrow wedges between them and the lines (rabbit.obj:
  /// a 12.29-degree wedge; the ten-sphere cluster: 10 folded edges, 18 corners).
  bool folds_more();
  /// (a, b) is a line edge once the proposed move is applied.
  bool line_after_move(int a, int b) const {
    const auto e = ekey(a, b);
    if (e == new_line_edge_) return true;
    if (renamed_from_ >= 0) {
      if (a == renamed_from_ || b == renamed_from_) return false;
      if (a == renamed_to_ && line_.count(ekey(renamed_from_, b))) return true;
      if (b == renamed_to_ && line_.count(ekey(a, renamed_from_))) return true;
    }
    return line_.count(e) > 0;
  }
  bool allow_folds_ = false;  // the last round: moves may fold (folds_more)
  std::vector<char> fold_refused_at_;  // per vertex (empty: none): a corner of a move folds_more refused
  int renamed_from_ = -1, renamed_to_ = -1;  // the proposed move's collapse: corner `from` becomes `to`
  std::pair<int, int> new_line_edge_{-1, -1};  // a line edge the move makes (a removal's)
  std::vector<int> fold_mark_;
  std::vector<V3> new_normals_;  // folds_more's scratch
  int fold_stamp_ = 0;
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

/// The faces within two rings of a face the cut made: the only ones moves come near.
std::vector<int> faces_near_cut(const Result& r, const std::vector<char>& cut);

}  // namespace mr::surface_union::slivers
