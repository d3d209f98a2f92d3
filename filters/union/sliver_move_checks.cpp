// What every move of the sliver step must pass before it is applied: within the deviation
// bound of the old faces and of the cut's surface, and crossing no face nearby (exact).
#include "union/sliver_collapser.h"

#include "union/exact.h"

namespace mr::surface_union::slivers {

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

bool Collapser::folds_more() {
  if (allow_folds_) return false;
  for (int f : replaced_)
    if (min_angle(f) < kMayFoldBelow) return false;
  auto unit = [](const V3& a, const V3& b, const V3& c) {
    V3 n = cross(sub3(b, a), sub3(c, a));
    const double l = norm(n);
    if (l > 0)
      for (double& k : n) k /= l;
    return n;
  };
  auto old_normal = [&](int f) { return unit(P(r_.faces[f][0]), P(r_.faces[f][1]), P(r_.faces[f][2])); };
  // After: a side off the lines where a new face meets another new face or an old neighbour
  // at more than a crease angle (the common answer is none: the rest is skipped).
  if (fold_mark_.size() != r_.faces.size()) fold_mark_.assign(r_.faces.size(), 0);
  const int stamp = ++fold_stamp_;
  for (int f : replaced_) fold_mark_[size_t(f)] = stamp;
  std::vector<V3>& normals = new_normals_;  // each new face's, once (every side reads two)
  normals.clear();
  for (const auto& q : new_pos_) normals.push_back(unit(q[0], q[1], q[2]));
  auto folds_after = [&] {
    for (size_t i = 0; i < new_ids_.size(); ++i) {
      const auto& t = new_ids_[i];
      const V3& n = normals[i];
      for (int z = 0; z < 3; ++z) {
        const int a = t[z], b = t[(z + 1) % 3];
        if (line_after_move(a, b)) continue;
        bool found = false;
        for (size_t j = 0; j < new_ids_.size() && !found; ++j) {
          if (j == i) continue;
          const auto& u = new_ids_[j];
          for (int y = 0; y < 3 && !found; ++y)
            if (u[y] == b && u[(y + 1) % 3] == a) {
              found = true;
              if (j > i && dot(n, normals[j]) < kCreaseCos) return true;
            }
        }
        if (found) continue;
        for (int h : vf_[b]) {
          if (!alive_[h] || fold_mark_[size_t(h)] == stamp) continue;
          const auto& u = r_.faces[h];
          for (int y = 0; y < 3; ++y)
            if (u[y] == b && u[(y + 1) % 3] == a && dot(n, old_normal(h)) < kCreaseCos) return true;
        }
      }
    }
    return false;
  };
  if (!folds_after()) return false;
  // Before: folded already at a side of the replaced faces off the lines, and the other
  // checks decide.
  for (int f : replaced_) {
    const auto& t = r_.faces[f];
    const V3 n = old_normal(f);
    for (int z = 0; z < 3; ++z) {
      const int a = t[z], b = t[(z + 1) % 3];
      if (line_.count(ekey(a, b))) continue;
      const int g = face_across(f, a, b);
      if (g >= 0 && dot(n, old_normal(g)) < kCreaseCos) return false;
    }
  }
  // Refused: the last round starts at the corners of the moves refused here.
  if (fold_refused_at_.empty()) fold_refused_at_.assign(r_.vertices.size(), 0);
  for (int f : replaced_)
    for (int x : r_.faces[f]) fold_refused_at_[size_t(x)] = 1;
  return true;
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

}  // namespace mr::surface_union::slivers
