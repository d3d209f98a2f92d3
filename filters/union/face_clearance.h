// Exact test whether two triangles of the output cross, and a grid of face boxes
// that finds the faces near a place, so that every sliver move can be checked
// against the rest of the surface (thin plates, nearly touching bodies) before it
// is applied.
#pragma once

#include "common/flat_index_map.h"
#include "union/vec3.h"

#include <array>
#include <cstdint>
#include <vector>

namespace mr::surface_union {

/// Triangles a and b (vertex ids and positions) intersect other than along what they
/// share; corners are shared when their ids or their positions are equal (shells that
/// only touch have distinct, coincident vertices). Exact (orientation predicates on
/// the doubles).
bool triangles_meet(const std::array<int, 3>& a, const V3 pa[3], const std::array<int, 3>& b, const V3 pb[3]);

/// The axis of the largest component of triangle T's normal: the projection on the other
/// two maps its plane one to one.
int largest_normal_axis(const V3 T[3]);

/// Faces (u, v, c) and (v, u, d) form a strictly convex quadrilateral lying exactly in
/// one plane. Flipping its diagonal to (c, d) then leaves the surface where it was,
/// so the flip cannot make faces meet that did not. Exact.
bool flat_convex_quad(const V3& u, const V3& v, const V3& c, const V3& d);

/// Uniform grid over the boxes of the faces of a mesh whose geometry changes. It only
/// grows: a face whose geometry changed is added again at its new place; a lookup
/// returns each face whose current box overlaps the query box exactly once.
class FaceGrid {
public:
  /// Levels of cells, each 4x coarser than the one below; a face is filed on the
  /// finest level whose cells are at least as large as its box, so long CAD faces and
  /// tiny slivers both cover a few cells. Holds references to the mesh.
  FaceGrid(const std::vector<V3>& vertices, const std::vector<std::array<int, 3>>& faces);
  /// Files face f at its current place (again, after its geometry changed).
  void add(int f);
  /// Face f is gone (lookups no longer return it until it is added again).
  void remove(int f);
  /// Faces whose box, as of their last add, overlaps [lo, hi], of those filed on
  /// `from_level` or coarser (0: all).
  void near(const V3& lo, const V3& hi, std::vector<int>& out, int from_level = 0) {
    near(lo, hi, out, from_level, marks_);
  }
  /// Which faces a lookup has listed already: one per thread looking up at once.
  struct Marks {
    std::vector<int> seen;
    int stamp = 0;
  };
  /// The same on a grid no thread changes meanwhile, with the caller's marks.
  void near(const V3& lo, const V3& hi, std::vector<int>& out, int from_level, Marks& marks) const;
  /// The level face f is filed on (-1: not filed).
  int level(int f) const { return level_[size_t(f)]; }
  void box(int f, V3& lo, V3& hi) const;
  /// Face f's box as of its last add (its current one, for a face refiled after each change).
  const std::array<V3, 2>& filed_box(int f) const { return boxes_[size_t(f)]; }

private:
  static constexpr int kLevels = 12;
  int64_t cell_of(double x, int k, int level) const;
  static int64_t key(int64_t i, int64_t j, int64_t k, int level) {
    return (i * 73856093) ^ (j * 19349663) ^ (k * 83492791) ^ (int64_t(level) << 58);
  }
  const std::vector<V3>& vertices_;
  const std::vector<std::array<int, 3>>& faces_;
  V3 origin_{0, 0, 0};
  double cell_ = 1;  // finest level
  int levels_used_ = 0;
  std::vector<int> level_faces_[kLevels];  // faces filed on each level (once per add)
  // Cells as singly linked lists in flat arrays (a node allocation per cell and per
  // face filed cost more than the lookups on a million faces): key -> list head.
  struct CellKeyHash {
    size_t operator()(int64_t k) const {
      const uint64_t h = uint64_t(k) * 0x9E3779B97F4A7C15ull;
      return size_t(h ^ (h >> 29));
    }
  };
  struct Entry {
    int face, next;
  };
  int* head_of(int64_t key);         // the list of a cell, or nullptr
  const int* head_of(int64_t key) const;
  int& head_or_new(int64_t key);     // the list of a cell, made if missing
  FlatIndexMap<int64_t, CellKeyHash> cell_index_;
  std::vector<int> heads_;           // per cell: first entry, -1 when empty
  std::vector<Entry> entries_;
  int free_entry_ = -1;              // removed entries, reused
  std::vector<std::array<V3, 2>> boxes_;  // as of the last add
  std::vector<int> level_;                // where each face is filed; -1: not filed
  Marks marks_;
};

}  // namespace mr::surface_union
