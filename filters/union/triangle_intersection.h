// Exact triangle-triangle intersection between faces of different bodies.
// Every topological decision is an exact orientation predicate; the points are
// exact rationals stored once in the point table (edge-face crossings are also
// cached by (edge, face), so the faces around an edge reuse the same point).
#pragma once

#include "common/flat_index_map.h"
#include "union/point_table.h"
#include "union/soup.h"

#include <cstdint>
#include <vector>

namespace mr::surface_union {

class PairIntersector {
public:
  /// `vertex_point[v]` is the point-table index of input vertex v.
  PairIntersector(const Soup& soup, PointTable& points, const std::vector<int>& vertex_point);

  /// Intersects faces f and g and appends what each receives to `cf[f]` and `cf[g]`.
  /// Returns true if they share at least one point. Handles crossing, touching at a
  /// point or along a segment, shared vertices and edges, and coplanar overlap.
  bool intersect(int f, int g, CutFaces& cf);

  /// A pair that may meet, with the signs of each face's corners against the other's
  /// plane (sx: g's corners against f; st: f's against g; coplanar when sx is all 0).
  struct Candidate {
    int pair;
    signed char sx[3], st[3];
  };
  /// Decides in parallel which of `pairs` may meet (the rest cannot, and need not be
  /// intersected) and builds the edge-face crossings those need, so that intersecting
  /// them only files the points. Returns them in pair order. Changes no output.
  std::vector<Candidate> prepare(const std::vector<std::pair<int, int>>& pairs);
  /// intersect() for a candidate from prepare(): its signs are not computed again.
  bool intersect(const std::pair<int, int>& pair, const Candidate& c, CutFaces& cf);
  /// Room for about `crossings` edge-face crossings in the cache.
  void reserve(size_t crossings) { edge_face_cache_.reserve(crossings); }

  int edge_face_points() const { return int(edge_face_cache_.size()); }

private:
  int edge_plane_point(int a, int b, int face);
  /// Where face f meets the plane of face `other` (its corners' sides `sign`): its
  /// corners on the plane and its sides' crossings, sorted and distinct (at most two).
  struct Section {
    int id[6];
    int n = 0;
  };
  void plane_section(int f, const int sign[3], int other, Section& out);
  bool coplanar(int f, int g, CutFaces& cf);
  bool sections_surely_apart(int f, const int* st, int g, const int* sx) const;
  const double* vp(int v) const { return soup_.vertex[v].data(); }

  const Soup& soup_;
  PointTable& points_;
  const std::vector<int>& vertex_point_;
  struct EFKey {
    int a, b, f;
    bool operator==(const EFKey& o) const { return a == o.a && b == o.b && f == o.f; }
  };
  struct EFHash {
    size_t operator()(const EFKey& k) const {
      uint64_t h = (uint64_t(uint32_t(k.a)) * 0x9E3779B97F4A7C15ull) ^ (uint64_t(uint32_t(k.b)) * 0xC2B2AE3D27D4EB4Full) ^
                   (uint64_t(uint32_t(k.f)) * 0x165667B19E3779F9ull);
      return size_t(h ^ (h >> 31));
    }
  };
  FlatIndexMap<EFKey, EFHash> edge_face_cache_;
  /// Crossings built by prepare(), taken by edge_plane_point() when first asked for.
  FlatIndexMap<EFKey, EFHash> prepared_index_;
  std::vector<QPoint> prepared_;
  /// The first steps of intersect(): false if f and g certainly do not meet; else the
  /// signs of each face's corners against the other's plane (coplanar: all sx zero).
  bool may_meet(int f, int g, int sx[3], int st[3]) const;
  bool intersect_crossing(int f, int g, const int sx[3], const int st[3], CutFaces& cf);
  /// The crossing of coplanar input edges (a, b) and (c, d), built once (neighbouring
  /// face pairs meet the same edge crossings again).
  int edge_edge_point(int a, int b, int c, int d, const Projection& pr);
  struct EEKey {
    int a, b, c, d;
    bool operator==(const EEKey& o) const { return a == o.a && b == o.b && c == o.c && d == o.d; }
  };
  struct EEHash {
    size_t operator()(const EEKey& k) const {
      uint64_t h = (uint64_t(uint32_t(k.a)) * 0x9E3779B97F4A7C15ull) ^ (uint64_t(uint32_t(k.b)) * 0xC2B2AE3D27D4EB4Full) ^
                   (uint64_t(uint32_t(k.c)) * 0x165667B19E3779F9ull) ^ (uint64_t(uint32_t(k.d)) * 0x27D4EB2F165667C5ull);
      return size_t(h ^ (h >> 31));
    }
  };
  FlatIndexMap<EEKey, EEHash> edge_edge_cache_;
};

}  // namespace mr::surface_union
