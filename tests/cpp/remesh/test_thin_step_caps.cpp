// Thin-step caps: a ledge between two walls facing the same way gets caps of 1.7 x its width at
// its corners; a wide ledge, a thin plate's rim (the surfaces beyond face apart) and a ledge
// shorter than an element get none; of a tapering ledge only the face at its
// narrow end caps. A strip between an edge and a seam in the flat side beyond it is capped too.
#include "remesh/thin_step_caps.h"
#include "common/coherent_orientation.h"
#include "features/feature_lines.h"
#include "shapes.h"

#include <gtest/gtest.h>

#include <array>
#include <utility>
#include <vector>

using namespace mr;

namespace {

// A closed prism: the polygon `profile` (x, z) swept along y from 0 to `length`, its two ends
// cut into `end_triangles` (indices into the profile). `top_x` moves profile points at the far
// end in x (index, new x): a profile that changes along the prism.
void prism(TriMesh& m, const std::vector<std::array<double, 2>>& profile,
           const std::vector<std::array<int, 3>>& end_triangles, double length,
           const std::vector<std::pair<int, double>>& far_x = {}) {
  const int n = int(profile.size());
  std::vector<Point3> points;
  for (double y : {0.0, length})
    for (const auto& p : profile) points.emplace_back(p[0], y, p[1]);
  for (const auto& [i, x] : far_x) points[size_t(n + i)][0] = x;
  std::vector<std::array<int, 3>> faces;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    faces.push_back({i, j, n + j});
    faces.push_back({i, n + j, n + i});
  }
  for (const auto& t : end_triangles) {
    faces.push_back(t);
    faces.push_back({n + t[0], n + t[2], n + t[1]});
  }
  test::build(m, points, faces);
  orient_coherently(m);
}

// A block 1 wide and 1 high with a wall 1 higher standing `width` in from its left side: the
// ledge between x = 0 and x = width at z = 1 (profile points 4 and 5).
const std::vector<std::array<double, 2>> kLedgeProfile(double width) {
  return {{0, 0}, {1, 0}, {1, 2}, {width, 2}, {width, 1}, {0, 1}};
}
const std::vector<std::array<int, 3>> kLedgeEnds = {{0, 1, 4}, {1, 2, 3}, {1, 3, 4}, {0, 4, 5}};

using CapRule = int (*)(const remesh::Surface&, const std::vector<std::array<bool, 3>>&, double, std::vector<double>&);

std::vector<double> caps_of(const TriMesh& m, double target, int& capped, CapRule rule = remesh::cap_thin_steps) {
  features::Params p;
  p.min_line_length = target;
  p.use_selected_edges_as_ridges = true;
  const features::Result fr = features::detect(m, p);
  const remesh::Surface s = remesh::Surface::from_mesh(m, fr.patch_of_face);
  std::vector<double> cap(m.vert.size(), 0.0);
  capped = rule(s, fr.ridge, target, cap);
  return cap;
}

}  // namespace

TEST(RemeshThinStepCaps, LedgeBetweenWallsFacingTheSameWayIsCappedAtItsCorners) {
  TriMesh m;
  const double width = 0.004, target = 0.05;
  prism(m, kLedgeProfile(width), kLedgeEnds, 1.0);
  int capped = 0;
  const std::vector<double> cap = caps_of(m, target, capped);
  EXPECT_EQ(capped, 2);  // the ledge's two faces
  const int n = 6;
  for (int v = 0; v < int(cap.size()); ++v) {
    const bool on_ledge = v % n == 4 || v % n == 5;
    if (on_ledge) EXPECT_NEAR(cap[size_t(v)], 1.7 * width, 1e-12) << v;
    else EXPECT_EQ(cap[size_t(v)], 0.0) << v;
  }
}

TEST(RemeshThinStepCaps, WideLedgeShortLedgeAndRimAreNotCapped) {
  int capped = -1;
  {
    TriMesh wide;  // 0.2 x target wide: the front meshes it as it is
    prism(wide, kLedgeProfile(0.01), kLedgeEnds, 1.0);
    caps_of(wide, 0.05, capped);
    EXPECT_EQ(capped, 0);
  }
  {
    TriMesh short_ledge;  // 0.04 long, under one element
    prism(short_ledge, kLedgeProfile(0.004), kLedgeEnds, 0.04);
    caps_of(short_ledge, 0.05, capped);
    EXPECT_EQ(capped, 0);
  }
  {
    TriMesh rim;  // a plate 0.004 thick: its rims' top and bottom face apart
    prism(rim, {{0, 0}, {1, 0}, {1, 0.004}, {0, 0.004}}, {{0, 1, 2}, {0, 2, 3}}, 1.0);
    caps_of(rim, 0.05, capped);
    EXPECT_EQ(capped, 0);
  }
}

TEST(RemeshThinStepCaps, TaperingLedgeIsCappedAtItsNarrowestWidthOnly) {
  // The wall leans in: the ledge narrows from 0.004 (y = 0) to 0.0008 (y = 1). Its face with a
  // corner at the wide end and its side on the other line sees that line close in beyond it (a
  // wedge) and is refused; the face at the narrow end caps its corners at 1.7 x 0.0008, raised to
  // the floor of 0.05 x target.
  TriMesh tapered;
  prism(tapered, kLedgeProfile(0.004), kLedgeEnds, 1.0, {{3, 0.0008}, {4, 0.0008}});
  int capped = -1;
  const std::vector<double> cap = caps_of(tapered, 0.05, capped);
  EXPECT_EQ(capped, 1);
  for (int v : {4, 10, 11}) EXPECT_NEAR(cap[size_t(v)], 0.05 * 0.05, 1e-12) << v;
  EXPECT_EQ(cap[5], 0.0);
}

TEST(RemeshThinStepCaps, StripBesideASeamInAFlatSideIsCapped) {
  // A block whose top is cut by a seam (selected edges, as a union's intersection line where two
  // bodies' coplanar sides meet) 0.004 in from its left edge: the strip between the edge and the
  // seam lies in the plane beyond the seam.
  const double width = 0.004;
  const int n = 5;
  for (bool seam : {true, false}) {
    TriMesh m;
    prism(m, {{0, 0}, {1, 0}, {1, 1}, {width, 1}, {0, 1}}, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}, 1.0);
    if (seam)
      for (auto& f : m.face)
        for (int z = 0; z < 3; ++z) {
          const int a = int(vcg::tri::Index(m, f.V(z))), b = int(vcg::tri::Index(m, f.V((z + 1) % 3)));
          if ((a == 3 && b == n + 3) || (a == n + 3 && b == 3)) f.SetFaceEdgeS(z);
        }
    int capped = -1;
    const std::vector<double> cap = caps_of(m, 0.05, capped);
    EXPECT_EQ(capped, seam ? 2 : 0);
    for (int v = 0; v < int(cap.size()); ++v) {
      const bool on_strip = seam && (v % n == 3 || v % n == 4);
      EXPECT_NEAR(cap[size_t(v)], on_strip ? 1.7 * width : 0.0, 1e-12) << v;
    }
  }
}

TEST(RemeshThinStepCaps, NarrowRimIsCappedByTheRimRuleAndAWideOneIsNot) {
  // A plate 0.004 thick (0.08 x target): its rims' top and bottom face apart. The rim rule caps
  // the corners of its rims' faces at 1.7 x the thickness; the step rule leaves them.
  const double target = 0.05;
  auto rim_caps = [&](double thickness, int& capped) {
    TriMesh plate;
    prism(plate, {{0, 0}, {1, 0}, {1, thickness}, {0, thickness}}, {{0, 1, 2}, {0, 2, 3}}, 1.0);
    return caps_of(plate, target, capped, remesh::cap_narrow_rims);
  };
  int capped = 0;
  const std::vector<double> cap = rim_caps(0.004, capped);
  EXPECT_EQ(capped, 8);  // the two faces of each of the four rims (x = 0, x = 1, y = 0, y = 1)
  for (double c : cap) EXPECT_NEAR(c, 1.7 * 0.004, 1e-12);
  rim_caps(0.6 * target, capped);  // 1.7 x 0.6 x target is over the target: nothing to gain
  EXPECT_EQ(capped, 0);
  // A ledge (the faces beyond it face the same way) is the step rule's, not the rim rule's.
  TriMesh ledge;
  prism(ledge, kLedgeProfile(0.004), kLedgeEnds, 1.0);
  caps_of(ledge, target, capped, remesh::cap_narrow_rims);
  EXPECT_EQ(capped, 0);
}
