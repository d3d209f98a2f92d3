#include "common/errors.h"
#include "features/feature_lines.h"
#include "shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

using namespace mr;

namespace {
features::Result detect(const TriMesh& m) { return features::detect(m, features::Params{}); }
using features::detect;

// Rotates every vertex about an arbitrary axis (rigid motion).
void rotate(TriMesh& m, double angle) {
  vcg::Matrix44d r;
  r.SetRotateRad(angle, Point3(1, 2, 3).Normalize());
  for (auto& v : m.vert) v.P() = r * v.P();
}
}  // namespace

TEST(FeatureLines, CubeHas12Ridges8Corners12Lines6Patches) {
  for (int n : {1, 4}) {
    TriMesh m;
    test::cube(m, n);
    auto r = detect(m);
    EXPECT_EQ(r.ridge_edges, 12 * n) << "n=" << n;
    EXPECT_EQ(r.corners.size(), 8u);
    EXPECT_EQ(r.lines.size(), 12u);
    EXPECT_EQ(r.patch_count, 6);
    for (const auto& line : r.lines) {
      EXPECT_FALSE(line.closed);
      EXPECT_EQ(line.vertices.size(), size_t(n + 1));
    }
  }
}

TEST(FeatureLines, EveryPatchOfTheCubeIsOneSquareSide) {
  TriMesh m;
  test::cube(m, 3);
  auto r = detect(m);
  std::vector<int> faces_per_patch(r.patch_count, 0);
  for (int p : r.patch_of_face) ++faces_per_patch[p];
  for (int count : faces_per_patch) EXPECT_EQ(count, 2 * 3 * 3);
}

TEST(FeatureLines, CylinderHasTwoClosedLinesNoCornersThreePatches) {
  TriMesh m;
  test::cylinder(m, 32, 4);
  auto r = detect(m);
  EXPECT_EQ(r.corners.size(), 0u);
  ASSERT_EQ(r.lines.size(), 2u);
  for (const auto& line : r.lines) {
    EXPECT_TRUE(line.closed);
    EXPECT_EQ(line.vertices.size(), 32u);
  }
  EXPECT_EQ(r.patch_count, 3);
  EXPECT_EQ(r.ridge_edges, 64);
}

TEST(FeatureLines, SphereIsOnePatchWithoutLines) {
  TriMesh m;
  test::sphere(m, 3);
  auto r = detect(m);
  EXPECT_EQ(r.patch_count, 1);
  EXPECT_EQ(r.lines.size(), 0u);
  EXPECT_EQ(r.ridge_edges, 0);
}

TEST(FeatureLines, OpenGridBoundaryIsRidgeWithFourCornersAtTheSquareCorners) {
  TriMesh m;
  test::grid(m, 5);
  auto r = detect(m);
  EXPECT_EQ(r.boundary_edges, 20);
  EXPECT_EQ(r.ridge_edges, 20);
  ASSERT_EQ(r.corners.size(), 4u);
  for (int c : r.corners) {
    const auto& p = m.vert[c].cP();
    EXPECT_TRUE((p[0] == 0 || p[0] == 1) && (p[1] == 0 || p[1] == 1));
  }
  EXPECT_EQ(r.lines.size(), 4u);
  EXPECT_EQ(r.patch_count, 1);
}

TEST(FeatureLines, CornerAngleDecidesWhetherASquareTurnIsACorner) {
  TriMesh m;
  test::grid(m, 2);
  features::Params p;
  p.corner_angle_deg = 100;  // the grid's 90-degree turns are no longer corners
  auto r = detect(m, p);
  EXPECT_EQ(r.corners.size(), 0u);
  ASSERT_EQ(r.lines.size(), 1u);
  EXPECT_TRUE(r.lines[0].closed);
}

TEST(FeatureLines, RidgeAngleThresholdIsStrict) {
  // Two triangles folded by 40 degrees: ridge at 30, not at 50.
  const double a = 40.0 * 3.14159265358979323846 / 180.0;
  TriMesh m;
  test::build(m, {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -std::cos(a), std::sin(a)}},
              {{0, 1, 2}, {1, 0, 3}});
  features::Params p;
  p.ridge_angle_deg = 30;
  EXPECT_EQ(detect(m, p).patch_count, 2);
  p.ridge_angle_deg = 50;
  EXPECT_EQ(detect(m, p).patch_count, 1);
}

TEST(FeatureLines, InconsistentOrientationDoesNotFakeARidge) {
  // A flat square of two triangles, the second one flipped.
  TriMesh m;
  test::build(m, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 3, 2}});
  auto r = detect(m);
  EXPECT_EQ(r.patch_count, 1);
  EXPECT_EQ(r.ridge_edges, 4);  // only the boundary
}

TEST(FeatureLines, NonManifoldEdgeIsARidge) {
  TriMesh m;
  test::build(m, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}},
              {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  auto r = detect(m);
  EXPECT_EQ(r.non_manifold_edges, 1);
  EXPECT_EQ(r.patch_count, 3);
}

TEST(FeatureLines, SelectedEdgesBecomeRidges) {
  TriMesh m;
  test::grid(m, 4);
  // select the diagonal of every square on the main diagonal: splits the grid into two patches
  features::Params p;
  p.use_selected_edges_as_ridges = true;
  auto base = detect(m, p);
  EXPECT_EQ(base.patch_count, 1);
  for (int i = 0; i < 4; ++i) m.face[2 * (i * 4 + i)].SetFaceEdgeS(2);  // edge (i,i)-(i+1,i+1)
  for (int i = 0; i < 4; ++i) m.face[2 * (i * 4 + i) + 1].SetFaceEdgeS(0);
  auto r = detect(m, p);
  EXPECT_EQ(r.patch_count, 2);
  EXPECT_EQ(r.ridge_edges, 16 + 4);
}

TEST(FeatureLines, SmallPatchesMergeIntoTheirLargestNeighbour) {
  TriMesh m;
  test::cube(m, 4);  // 32 faces per side, spacing 0.5
  // Pull the centre of the +x side out into a steep pyramid: its faces become tiny patches.
  for (auto& v : m.vert)
    if (v.P() == Point3(1, 0, 0)) v.P() = Point3(1.5, 0, 0);
  auto bumpy = detect(m);
  EXPECT_GT(bumpy.patch_count, 6);
  features::Params p;
  p.min_patch_faces = 10;
  auto merged = detect(m, p);
  EXPECT_EQ(merged.patch_count, 6);
  EXPECT_GE(merged.merged_patches, 1);
  EXPECT_EQ(merged.corners.size(), 8u);
}

namespace {
// A flat 10 x 10 grid folded along x = 0.5 by an amount that fades with y: a crease from the
// boundary at y = 0 that ends inside the surface (a dangling end), as noisy scans have them.
void fading_crease(TriMesh& m) {
  test::grid(m, 10);
  for (auto& v : m.vert) {
    const double fade = (1 - v.P()[1]) * (1 - v.P()[1]);
    v.P()[2] = 2.0 * std::abs(v.P()[0] - 0.5) * fade;
  }
}

double line_length(const TriMesh& m, const features::DiscreteLine& line) {
  double length = 0;
  const size_t n = line.vertices.size();
  for (size_t k = 0; k + 1 < n + (line.closed ? 1 : 0); ++k)
    length += (m.vert[line.vertices[k]].cP() - m.vert[line.vertices[(k + 1) % n]].cP()).Norm();
  return length;
}
}  // namespace

TEST(FeatureLines, ShortDanglingCreaseIsDroppedByMinLineLength) {
  TriMesh m;
  fading_crease(m);
  const auto strict = detect(m);
  ASSERT_GT(strict.ridge_edges, strict.boundary_edges);  // the crease is there
  double crease = 0;
  for (const auto& line : strict.lines) {
    const auto& a = m.vert[line.vertices.front()].cP();
    const auto& b = m.vert[line.vertices.back()].cP();
    if (a[0] == 0.5 && b[0] == 0.5) crease = line_length(m, line);
  }
  ASSERT_GT(crease, 0.2);
  features::Params p;
  p.min_line_length = 0.9 * crease;  // shorter than the crease: everything stays
  const auto kept = detect(m, p);
  EXPECT_EQ(kept.ridge_edges, strict.ridge_edges);
  EXPECT_EQ(kept.corners, strict.corners);
  EXPECT_EQ(kept.suppressed_lines, 0);
  p.min_line_length = 1.1 * crease;  // longer: the crease goes, the boundary always stays
  const auto dropped = detect(m, p);
  EXPECT_EQ(dropped.suppressed_lines, 1);
  EXPECT_EQ(dropped.ridge_edges, dropped.boundary_edges);
  EXPECT_EQ(dropped.suppressed_ridge_edges, strict.ridge_edges - dropped.ridge_edges);
  EXPECT_LT(dropped.corners.size(), strict.corners.size());
  EXPECT_EQ(dropped.patch_count, 1);
}

TEST(FeatureLines, ShortClosedLoopsAreDroppedAndLongOnesKept) {
  TriMesh m;
  test::cylinder(m, 32, 4);  // two rim circles of perimeter about 2 pi
  features::Params p;
  p.min_line_length = 6.0;
  auto r = detect(m, p);
  EXPECT_EQ(r.lines.size(), 2u);
  EXPECT_EQ(r.suppressed_lines, 0);
  p.min_line_length = 6.5;
  r = detect(m, p);
  EXPECT_EQ(r.lines.size(), 0u);
  EXPECT_EQ(r.suppressed_lines, 2);
  EXPECT_EQ(r.patch_count, 1);
}

// A flat rhombus A-E-B-D with its middle diagonal A-B bent into a sliver A-B-C (C lifted, its
// normal 45 degrees off): A-B, B-C and C-A are ridges by angle and enclose a one-face patch.
TEST(FeatureLines, SliverPatchesAreDroppedOnlyWhenTheyAreSmallAndThin) {
  TriMesh m;
  test::build(m, {{0, 0, 0}, {20, 0, 0}, {10, 0.3, 0.3}, {10, 20, 0}, {10, -20, 0}},
              {{0, 4, 1}, {0, 1, 2}, {0, 2, 3}, {2, 1, 3}});
  features::Params p;
  const auto strict = detect(m, p);
  ASSERT_EQ(strict.ridge_edges, 7);  // 4 boundary + 3 around the sliver
  ASSERT_EQ(strict.patch_count, 3);  // below A-B, the sliver, above A-B (split by no ridge)
  // Area 4.24 and border 40: thin (4.24 < 0.02 x 40^2) and small (4.24 < 0.1 x 8^2): it goes.
  p.min_line_length = 8.0;
  const auto dropped = detect(m, p);
  EXPECT_EQ(dropped.ridge_edges, 4);
  EXPECT_EQ(dropped.patch_count, 1);
  EXPECT_EQ(dropped.suppressed_ridge_edges, 3);
  // Under 0.1 x 6^2 = 3.6 it is not small: it stays.
  p.min_line_length = 6.0;
  const auto kept = detect(m, p);
  EXPECT_EQ(kept.ridge_edges, 7);
  EXPECT_EQ(kept.patch_count, 3);
}

TEST(FeatureLines, SliverPatchesBorderedByAFoldStayWithKeepFoldedSlivers) {
  // The sliver of the test above stood up (corner 2 raised to z = 3): along A-B it meets the
  // face below at a fold (normals about 84 degrees apart), as the needles box.STL's union leaves
  // at the plates' corners do.
  TriMesh m;
  test::build(m, {{0, 0, 0}, {20, 0, 0}, {10, 0.3, 3}, {10, 20, 0}, {10, -20, 0}},
              {{0, 4, 1}, {0, 1, 2}, {0, 2, 3}, {2, 1, 3}});
  const Point3 below = vcg::NormalizedTriangleNormal(m.face[0]), sliver = vcg::NormalizedTriangleNormal(m.face[1]);
  ASSERT_LT(below * sliver, 0.5);  // a fold: over 60 degrees
  features::Params p;
  p.min_line_length = 20.0;  // area 30.1 < 0.1 x 20^2 and < 0.02 x 40.9^2: small and thin
  const auto dropped = detect(m, p);
  EXPECT_GT(dropped.suppressed_ridge_edges, 0);
  EXPECT_EQ(dropped.patch_of_face[1], dropped.patch_of_face[0]);  // merged across the fold
  EXPECT_EQ(dropped.suppressed_folded_slivers, 1);
  p.keep_folded_slivers = true;
  const auto kept = detect(m, p);
  EXPECT_EQ(kept.suppressed_ridge_edges, 0);
  EXPECT_EQ(kept.suppressed_folded_slivers, 0);
  for (int f : {0, 2, 3}) EXPECT_NE(kept.patch_of_face[1], kept.patch_of_face[f]) << f;
}

// The sliver turned over (corner 2 just across A-B, below it): its normal is nearly opposite to
// all three neighbours', a crumple as a union's sliver step can leave on a flat side. It is
// dropped where a sliver of its area would stay (not small: 3.04 > 0.1 x 4^2), since it is
// thinner than the line length (mean width 2 x area / border 0.15), and kept for
// keep_folded_slivers and where the line length is under its width.
TEST(FeatureLines, CrumplesAreDroppedWhereSliversOfTheirAreaStay) {
  TriMesh m;
  test::build(m, {{0, 0, 0}, {20, 0, 0}, {10, -0.3, 0.05}, {10, 20, 0}, {10, -20, 0}},
              {{0, 4, 1}, {0, 1, 2}, {0, 2, 3}, {2, 1, 3}});
  const Point3 crumple = vcg::NormalizedTriangleNormal(m.face[1]);
  for (int f : {0, 2, 3}) ASSERT_LT(crumple * vcg::NormalizedTriangleNormal(m.face[f]), -0.9) << f;
  features::Params p;
  p.min_line_length = 4.0;
  const auto dropped = detect(m, p);
  EXPECT_EQ(dropped.ridge_edges, 4);
  EXPECT_EQ(dropped.patch_count, 1);
  EXPECT_EQ(dropped.suppressed_folded_slivers, 1);
  p.keep_folded_slivers = true;
  const auto kept = detect(m, p);
  EXPECT_EQ(kept.ridge_edges, 7);
  EXPECT_EQ(kept.patch_count, 3);
  p.keep_folded_slivers = false;
  p.min_line_length = 0.1;
  EXPECT_EQ(detect(m, p).ridge_edges, 7);
  // A-B selected (an intersection line passing along the crumple): the crumple still goes, and
  // A-B with it; a selected edge bounding a sliver that is not turned over stays (below).
  m.face[0].SetFaceEdgeS(2);
  m.face[1].SetFaceEdgeS(0);
  p.use_selected_edges_as_ridges = true;
  p.min_line_length = 4.0;
  const auto selected = detect(m, p);
  EXPECT_EQ(selected.ridge_edges, 4);
  EXPECT_EQ(selected.patch_count, 1);
  // The same sliver not turned over (45 degrees off its neighbours) stays at 4.
  TriMesh bent;
  test::build(bent, {{0, 0, 0}, {20, 0, 0}, {10, 0.3, 0.3}, {10, 20, 0}, {10, -20, 0}},
              {{0, 4, 1}, {0, 1, 2}, {0, 2, 3}, {2, 1, 3}});
  p.min_line_length = 8.0;  // small and thin: it goes (the test above), but not with A-B selected
  bent.face[0].SetFaceEdgeS(2);
  bent.face[1].SetFaceEdgeS(0);
  EXPECT_EQ(detect(bent, p).ridge_edges, 7);
  p.use_selected_edges_as_ridges = false;
  p.min_line_length = 4.0;
  EXPECT_EQ(detect(bent, p).ridge_edges, 7);
}

TEST(FeatureLines, NetworksWithoutDanglingEndsAreNeverDropped) {
  TriMesh m;
  test::cube(m, 2);  // every corner is on three ridges
  features::Params p;
  p.min_line_length = 100.0;
  auto r = detect(m, p);
  EXPECT_EQ(r.ridge_edges, 24);
  EXPECT_EQ(r.corners.size(), 8u);
  EXPECT_EQ(r.patch_count, 6);
  EXPECT_EQ(r.suppressed_lines, 0);
}

TEST(FeatureLines, PatchCountStableUnderRotation) {
  TriMesh m;
  test::cylinder(m, 40, 3);
  auto before = detect(m);
  rotate(m, 0.7);
  auto after = detect(m);
  EXPECT_EQ(before.patch_count, after.patch_count);
  EXPECT_EQ(before.ridge_edges, after.ridge_edges);
  EXPECT_EQ(before.corners, after.corners);
}

TEST(FeatureLines, DeterministicOutput) {
  TriMesh m;
  test::cube(m, 3);
  auto a = detect(m), b = detect(m);
  EXPECT_EQ(a.patch_of_face, b.patch_of_face);
  EXPECT_EQ(a.corners, b.corners);
  ASSERT_EQ(a.lines.size(), b.lines.size());
  for (size_t i = 0; i < a.lines.size(); ++i) EXPECT_EQ(a.lines[i].vertices, b.lines[i].vertices);
}

TEST(FeatureLines, BadParametersAreRejected) {
  TriMesh m;
  test::cube(m, 1);
  features::Params p;
  p.ridge_angle_deg = 0;
  EXPECT_THROW(detect(m, p), InvalidInput);
  p = {};
  p.corner_angle_deg = -1;
  EXPECT_THROW(detect(m, p), InvalidInput);
  p = {};
  p.min_patch_faces = -3;
  EXPECT_THROW(detect(m, p), InvalidInput);
  p = {};
  p.min_line_length = -1;
  EXPECT_THROW(detect(m, p), InvalidInput);
  TriMesh empty;
  EXPECT_THROW(detect(empty), InvalidInput);
}

TEST(FeatureLines, RandomSoupWithDegenerateFacesNeverBreaks) {
  // Random faces over few vertices: repeated indices, zero areas, edges on many faces.
  std::mt19937 rng(7);
  for (int round = 0; round < 20; ++round) {
    const int nv = 6 + round;
    std::uniform_int_distribution<int> pick(0, nv - 1);
    std::uniform_real_distribution<double> coord(-1, 1);
    std::vector<Point3> pts;
    for (int i = 0; i < nv; ++i) pts.push_back(Point3(coord(rng), coord(rng), round % 3 == 0 ? 0.0 : coord(rng)));
    pts[1] = pts[0];  // a duplicated point
    std::vector<std::array<int, 3>> faces;
    for (int f = 0; f < 3 * nv; ++f) faces.push_back({pick(rng), pick(rng), pick(rng)});
    TriMesh m;
    test::build(m, pts, faces);
    features::Params p;
    p.min_patch_faces = 3;
    auto r = detect(m, p);
    ASSERT_EQ(r.patch_of_face.size(), faces.size());
    for (int id : r.patch_of_face) {
      EXPECT_GE(id, 0);
      EXPECT_LT(id, r.patch_count);
    }
    size_t line_vertices = 0;
    for (const auto& line : r.lines) line_vertices += line.vertices.size();
    EXPECT_LE(r.lines.size(), size_t(r.ridge_edges));
    EXPECT_GE(line_vertices, r.lines.size());
  }
}
