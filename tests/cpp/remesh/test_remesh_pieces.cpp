// Unit tests of the remesher's pieces.
#include "remesh/advancing_front.h"
#include "remesh/feature_front.h"
#include "remesh/line_sliding.h"
#include "remesh/patch_retry.h"
#include "remesh/point_grid.h"
#include "remesh/size_field.h"
#include "remesh/strip_staggering.h"
#include "remesh/surface_recovery.h"
#include "remesh/surface_locator.h"
#include "remesh/triangle_geometry.h"
#include "shapes.h"
#include "unit_square.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace mr;
using namespace mr::remesh;
using P2 = vcg::Point2d;

namespace {

// The smallest angle of `out`'s faces, in degrees.
double worst_degrees(const OutputMesh& out) {
  double w = 1e9;
  for (const auto& f : out.faces) w = std::min(w, min_angle(out.points, f));
  return w * 180.0 / 3.14159265358979323846;
}

}  // namespace

TEST(RemeshPieces, CrossingCheck2D) {
  EXPECT_TRUE(segments_cross_2d(P2(0, 0), P2(2, 2), P2(0, 2), P2(2, 0), 1e-12));
  EXPECT_FALSE(segments_cross_2d(P2(0, 0), P2(1, 1), P2(0, 2), P2(2, 2), 1e-12));
  // Sharing an end point is not a crossing.
  EXPECT_FALSE(segments_cross_2d(P2(0, 0), P2(1, 0), P2(1, 0), P2(2, 1), 1e-12));
  // A T touching the interior is not a proper crossing but collinear overlap is.
  EXPECT_TRUE(segments_cross_2d(P2(0, 0), P2(2, 0), P2(1, 0), P2(3, 0), 1e-12));
  EXPECT_FALSE(segments_cross_2d(P2(0, 0), P2(1, 0), P2(2, 0), P2(3, 0), 1e-12));
  EXPECT_TRUE(strictly_inside_2d(P2(0.2, 0.2), P2(0, 0), P2(1, 0), P2(0, 1), 1e-12));
  EXPECT_FALSE(strictly_inside_2d(P2(0.5, 0.5), P2(0, 0), P2(1, 0), P2(0, 1), 1e-12));
}

TEST(RemeshPieces, ClosestPointOnTriangle) {
  std::array<double, 3> bary;
  const Point3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  Point3 q = closest_point_on_triangle(Point3(0.25, 0.25, 3), a, b, c, bary);
  EXPECT_NEAR((q - Point3(0.25, 0.25, 0)).Norm(), 0, 1e-12);
  EXPECT_NEAR(bary[0], 0.5, 1e-12);
  q = closest_point_on_triangle(Point3(2, -1, 0), a, b, c, bary);
  EXPECT_NEAR((q - b).Norm(), 0, 1e-12);
}

TEST(RemeshPieces, HostFaceSearchWalkGridAndBruteForce) {
  TriMesh m;
  test::sphere(m, 3);
  const Surface s = Surface::from_mesh(m, {});
  const SurfaceLocator loc(s, 0.1);
  const Point3 p = Point3(1, 1, 1).Normalize() * 1.001;
  // Reference: brute-force closest face.
  int ref = -1;
  double best = 1e9;
  for (size_t f = 0; f < s.faces.size(); ++f) {
    std::array<double, 3> bary;
    const double d = (closest_point_on_triangle(p, s.points[s.faces[f][0]], s.points[s.faces[f][1]], s.points[s.faces[f][2]], bary) - p).Norm();
    if (d < best) { best = d; ref = int(f); }
  }
  SearchStep step;
  Projection pr = loc.locate(p, -1, p, ref, 0.2, &step);
  EXPECT_EQ(step, SearchStep::Walk);
  EXPECT_NEAR(pr.distance, best, 1e-12);
  // Without a start face the grid answers.
  pr = loc.locate(p, -1, p, -1, 0.2, &step);
  EXPECT_EQ(step, SearchStep::Grid);
  EXPECT_NEAR(pr.distance, best, 1e-12);
  // Far away: brute force still answers.
  pr = loc.locate(p * 5, -1, p, -1, 0.1, &step);
  EXPECT_EQ(step, SearchStep::BruteForce);
  EXPECT_GE(pr.face, 0);
  // A normal that disagrees (n_face . n_point <= 0.5) excludes the near side of the sphere.
  pr = loc.locate(p, -1, -p, -1, 0.2, &step);
  EXPECT_GT(pr.distance, 1.5);
}

TEST(RemeshPieces, GrowingSearchFindsTheClosestFaceAtEveryDistance) {
  TriMesh m;
  test::sphere(m, 3);
  const Surface s = Surface::from_mesh(m, {});
  const SurfaceLocator loc(s, 0.1);
  // Points at 0.001 to 0.3 off the unit sphere, inside and out: the search from 0.01 on must
  // give the same distance as brute force, and nothing beyond its reach.
  for (int k = 0; k < 60; ++k) {
    const double off = (k % 2 ? 1 : -1) * 0.001 * std::pow(1.1, k);
    const Point3 dir = Point3(std::cos(k * 0.7), std::sin(k * 1.3), std::cos(k * 2.1)).Normalize();
    const Point3 p = dir * (1 + off);
    double best = 1e9;
    for (const auto& t : s.faces) {
      std::array<double, 3> bary;
      best = std::min(best, (closest_point_on_triangle(p, s.points[t[0]], s.points[t[1]], s.points[t[2]], bary) - p).Norm());
    }
    const Projection pr = loc.locate_growing(p, -1, -1, 0.01, 0.5);
    ASSERT_GE(pr.face, 0);
    EXPECT_NEAR(pr.distance, best, 1e-12);
  }
  EXPECT_LT(loc.locate_growing(Point3(3, 0, 0), -1, -1, 0.01, 0.5).face, 0);
}

TEST(RemeshPieces, SizeFieldUniformCurvatureAndGradation) {
  TriMesh m;
  test::sphere(m, 3);
  const Surface s = Surface::from_mesh(m, {});
  SizeParams sp;
  sp.target_length = 0.5;
  const SizeField uniform(s, sp);
  EXPECT_DOUBLE_EQ(uniform.min_size(), 0.5);
  EXPECT_DOUBLE_EQ(uniform.max_size(), 0.5);
  // Chord error on the unit sphere: h = sqrt(8 * e * R) with R about 1.
  sp.max_surface_error = 0.001;
  const SizeField curved(s, sp);
  EXPECT_NEAR(curved.max_size(), std::sqrt(8 * 0.001), 0.02);
  // Gradation: one small source, sizes grow with slope (g - 1) away from it.
  sp.max_surface_error = 0;
  sp.gradation = 1.2;
  sp.source_points = {s.points[0]};
  sp.source_sizes = {0.05};
  const SizeField graded(s, sp);
  EXPECT_NEAR(graded.at_vertex(0), 0.05, 1e-12);
  for (size_t v = 0; v < s.points.size(); ++v)
    EXPECT_LE(graded.at_vertex(int(v)), 0.05 + 0.2 * (s.points[v] - s.points[0]).Norm() + 1e-12);
}

TEST(RemeshPieces, SizeFieldLineSourceInterpolatesAlongTheSegmentAndGrades) {
  TriMesh m;
  test::sphere(m, 3);
  const Surface s = Surface::from_mesh(m, {});
  SizeParams sp;
  sp.target_length = 0.5;
  sp.gradation = 1.2;
  // A diameter between two antipodal vertices (0 and 3 of the icosahedron), 0.02 at one end, 0.1 at the other.
  const Point3 a = s.points[0], b = s.points[3];
  ASSERT_NEAR((a + b).Norm(), 0.0, 1e-12);
  sp.source_points = {a, b};
  sp.source_sizes = {0.02, 0.1};
  sp.source_segments = {{0, 1}};
  const SizeField field(s, sp);
  EXPECT_NEAR(field.at_vertex(0), 0.02, 1e-12);
  EXPECT_NEAR(field.at_vertex(3), 0.1, 1e-12);
  int below_target = 0;
  for (size_t v = 0; v < s.points.size(); ++v) {
    const Point3& p = s.points[v];
    const double t = std::clamp(((p - a) * (b - a)) / (b - a).SquaredNorm(), 0.0, 1.0);
    const double off = (p - (a + (b - a) * t)).Norm();
    // Never above the source's law (interpolated along the segment, graded away from it).
    EXPECT_LE(field.at_vertex(int(v)), (1 - t) * 0.02 + t * 0.1 + 0.2 * off + 1e-12);
    below_target += field.at_vertex(int(v)) < 0.5 ? 1 : 0;
  }
  // Every sphere point is within 1 of the diameter, so the line source reaches all of them.
  EXPECT_EQ(below_target, int(s.points.size()));
}

TEST(RemeshPieces, SizeSourcesReachEveryVertexTheirLawLowers) {
  // Sources only search the vertices within (target - size) / slope of them: on a fine grid
  // with a small target most vertices are beyond, and every vertex must still get exactly
  // min(target, the sources' graded laws) (the laws already respect the gradation).
  TriMesh m;
  test::grid(m, 40);
  const Surface s = Surface::from_mesh(m, {});
  SizeParams sp;
  sp.target_length = 0.05;
  sp.gradation = 1.3;
  sp.source_points = {Point3(0.5, 0.5, 0), Point3(0.1, 0.9, 0), Point3(0.9, 0.9, 0)};
  sp.source_sizes = {0.005, 0.01, 0.03};
  sp.source_segments = {{1, 2}};
  const SizeField field(s, sp);
  int lowered = 0;
  for (size_t v = 0; v < s.points.size(); ++v) {
    const Point3& p = s.points[v];
    double law = std::min(sp.target_length, 0.005 + 0.3 * (p - sp.source_points[0]).Norm());
    const Point3 a = sp.source_points[1], d = sp.source_points[2] - a;
    const double t = std::clamp(((p - a) * d) / d.SquaredNorm(), 0.0, 1.0);
    law = std::min(law, (1 - t) * 0.01 + t * 0.03 + 0.3 * (p - (a + d * t)).Norm());
    EXPECT_NEAR(field.at_vertex(int(v)), law, 1e-12) << v;
    lowered += law < sp.target_length ? 1 : 0;
  }
  EXPECT_GT(lowered, 20);
  EXPECT_LT(lowered, int(s.points.size()) / 2);  // most vertices are out of reach
}

TEST(RemeshPieces, FrontPriorityTakesSmallestFirstAndPenalisesFailures) {
  EXPECT_LT(front_priority(1.0, 0), front_priority(2.0, 0));
  EXPECT_LT(front_priority(2.0, 0), front_priority(1.0, 1));
}

TEST(RemeshPieces, AdvancingFrontFillsASquare) {
  const test::UnitSquare sq(0.1);
  OutputMesh out;
  const std::vector<FrontSide> front = test::UnitSquare::boundary(out);
  const FrontResult r = advance_front(out, front, 0, sq.locator, sq.size);
  EXPECT_EQ(r.unmeshed_sides, 0);
  double area = 0;
  for (const auto& f : out.faces) {
    const Point3 n = (out.points[f[1]] - out.points[f[0]]) ^ (out.points[f[2]] - out.points[f[0]]);
    EXPECT_GT(n[2], 0);  // oriented like the input
    area += 0.5 * n[2];
  }
  EXPECT_NEAR(area, 1.0, 1e-9);
}

TEST(RemeshPieces, RunWideWorkBudgetStopsTheFrontsAndIsShared) {
  // The whole square needs about 230 faces; a budget spent after a few candidate checks stops
  // the front with the limit reported, and a second front given the spent budget does nothing.
  const test::UnitSquare sq(0.1);
  long checks_left = 50;
  FrontParams fp;
  fp.checks_left = &checks_left;
  OutputMesh out;
  const FrontResult r = advance_front(out, test::UnitSquare::boundary(out), 0, sq.locator, sq.size, fp);
  EXPECT_TRUE(r.iteration_limit);
  EXPECT_GT(r.unmeshed_sides, 0);
  EXPECT_LE(checks_left, 0);
  EXPECT_LT(r.faces, 50);
  OutputMesh out2;
  const FrontResult r2 = advance_front(out2, test::UnitSquare::boundary(out2), 0, sq.locator, sq.size, fp);
  EXPECT_TRUE(r2.iteration_limit);
  EXPECT_EQ(r2.faces, 0);
  // With room to spare the same square is filled and the budget is charged for it.
  checks_left = 1000000;
  OutputMesh out3;
  const FrontResult r3 = advance_front(out3, test::UnitSquare::boundary(out3), 0, sq.locator, sq.size, fp);
  EXPECT_EQ(r3.unmeshed_sides, 0);
  EXPECT_FALSE(r3.iteration_limit);
  EXPECT_LT(checks_left, 1000000);
}

TEST(RemeshPieces, FrontThatCannotCloseTerminatesAndReports) {
  // The square's boundary run clockwise puts the "unmeshed" side outside the patch: the front
  // can place nothing valid there and must stop with its sides reported, not loop.
  const test::UnitSquare sq(0.1);
  OutputMesh out;
  const std::vector<FrontSide> front = test::UnitSquare::boundary(out, false);
  const FrontResult r = advance_front(out, front, 0, sq.locator, sq.size);
  EXPECT_GT(r.unmeshed_sides, 0);
  EXPECT_FALSE(r.iteration_limit);
  // Whatever was generated lies on the patch.
  for (const auto& p : out.points) {
    EXPECT_GE(p[0], -1e-9);
    EXPECT_LE(p[0], 1 + 1e-9);
  }
}

TEST(RemeshPieces, SmallClockwiseLoopIsNotClosedByTheLastResort) {
  // The unit square's four sides run clockwise: what lies to their left is off the surface. The
  // front can place nothing there, and the last-resort closure of small loops must not fill the
  // square either (that would cover a region that is not this loop's to mesh).
  TriMesh m;
  test::grid(m, 4);
  const Surface s = Surface::from_mesh(m, {});
  const SurfaceLocator loc(s, 0.1);
  const SizeField size(s, std::vector<double>(s.points.size(), 1.0));
  OutputMesh out;
  const int a = out.add_point(Point3(0, 0, 0), -1, PointKind::Corner), b = out.add_point(Point3(1, 0, 0), -1, PointKind::Corner),
            c = out.add_point(Point3(1, 1, 0), -1, PointKind::Corner), d = out.add_point(Point3(0, 1, 0), -1, PointKind::Corner);
  const FrontResult r = advance_front(out, {{b, a}, {c, b}, {d, c}, {a, d}}, 0, loc, size);
  EXPECT_EQ(r.faces, 0);
  EXPECT_EQ(r.unmeshed_sides, 4);
  // Run counter-clockwise the same loop is a hole of the patch and gets filled.
  OutputMesh out2;
  const int a2 = out2.add_point(Point3(0, 0, 0), -1, PointKind::Corner), b2 = out2.add_point(Point3(1, 0, 0), -1, PointKind::Corner),
            c2 = out2.add_point(Point3(1, 1, 0), -1, PointKind::Corner), d2 = out2.add_point(Point3(0, 1, 0), -1, PointKind::Corner);
  const FrontResult r2 = advance_front(out2, {{a2, b2}, {b2, c2}, {c2, d2}, {d2, a2}}, 0, loc, size);
  EXPECT_EQ(r2.unmeshed_sides, 0);
  EXPECT_GE(r2.faces, 2);
}

TEST(RemeshPieces, PolylineGapIsTheLargestDistanceBothWays) {
  const std::vector<Point3> straight{Point3(0, 0, 0), Point3(2, 0, 0)};
  const std::vector<Point3> bent{Point3(0, 0, 0), Point3(1, 0.01, 0), Point3(2, 0, 0)};
  EXPECT_NEAR(polyline_gap(straight, bent), 0.01, 1e-12);
  EXPECT_NEAR(polyline_gap(bent, straight), 0.01, 1e-12);
  EXPECT_NEAR(polyline_gap(straight, {Point3(0, 0, 0), Point3(1, 0, 0)}), 1.0, 1e-12);
}

TEST(RemeshPieces, CornerWithAFanClosedAllRoundIsPinchedAndOneBorderedTwiceIsNot) {
  // Corner 0 at the origin. Patch 0 has a fan of three faces closed all round it (points 1-3)
  // and, apart from it, face (0, 4, 5): a pinch. Patch 1 borders line point 6 twice with two
  // open fans (faces (6, 7, 8) and (6, 9, 10), a patch wrapping round): not a pinch.
  remesh::OutputMesh out;
  for (const Point3& p : {Point3(0, 0, 0), Point3(1, 0, 0), Point3(-0.5, 1, 0), Point3(-0.5, -1, 0),
                          Point3(3, 0, 0), Point3(3, 1, 0), Point3(10, 0, 0), Point3(11, 0, 0),
                          Point3(11, 1, 0), Point3(9, 0, 0), Point3(9, -1, 0)})
    out.add_point(p, 0, remesh::PointKind::Free);
  out.kind[0] = remesh::PointKind::Corner;
  out.kind[4] = out.kind[5] = out.kind[6] = out.kind[7] = out.kind[9] = remesh::PointKind::Line;
  out.faces = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {0, 4, 5}, {6, 7, 8}, {6, 9, 10}};
  out.face_patch = {0, 0, 0, 0, 1, 1};
  EXPECT_EQ(remesh::pinched_points(out, 0), std::vector<int>{0});
  EXPECT_TRUE(remesh::pinched_points(out, 1).empty());
  out.faces.pop_back();  // the closed fan alone (a dangling line's end inside the patch) is fine
  out.face_patch.pop_back();
  out.faces.erase(out.faces.begin() + 3);
  out.face_patch.erase(out.face_patch.begin() + 3);
  EXPECT_TRUE(remesh::pinched_points(out, 0).empty());
}

TEST(RemeshPieces, PinchedPointHasTwoFansAndRemovingAPatchKeepsTheOthers) {
  // Two triangles of patch 0 touching only at free point 0 (a bowtie), one triangle of patch 1.
  remesh::OutputMesh out;
  for (const Point3& p : {Point3(0, 0, 0), Point3(1, 0, 0), Point3(1, 1, 0), Point3(-1, 0, 0), Point3(-1, -1, 0),
                          Point3(2, 0, 0)})
    out.add_point(p, 0, remesh::PointKind::Free);
  out.kind[1] = out.kind[2] = out.kind[5] = remesh::PointKind::Line;
  out.faces = {{0, 1, 2}, {0, 3, 4}, {1, 5, 2}};
  out.face_patch = {0, 0, 1};
  out.shared_edges = {remesh::OutputMesh::edge_key(1, 2), remesh::OutputMesh::edge_key(1, 5),
                      remesh::OutputMesh::edge_key(5, 2)};
  EXPECT_EQ(remesh::pinched_points(out, 0).size(), 1u);
  EXPECT_TRUE(remesh::pinched_points(out, 1).empty());
  out.faces.push_back({0, 2, 3});  // the fans join: no longer pinched
  out.face_patch.push_back(0);
  EXPECT_TRUE(remesh::pinched_points(out, 0).empty());
  remesh::remove_patch_faces(out, 0);
  ASSERT_EQ(out.faces.size(), 1u);
  EXPECT_EQ(out.face_patch[0], 1);
  EXPECT_EQ(out.shared_edges.size(), 3u);  // patch 1's edges between line points stay taken
}

TEST(RemeshPieces, LinePointSlidesAlongItsLineAtAConvergingCreaseTip) {
  // Two lines leave a corner 19.3 degrees apart with points at 1 and 2 on both: the face between
  // the first pair and the next point of line A has 17.4 degrees. The first point of line B
  // slides along B (here straight) until no face of its ring is below the tip's 19.3 degrees,
  // and where the tip is the smallest, which no slide changes, the faces beyond it decide.
  const double alpha = 19.3 * 3.14159265358979323846 / 180.0;
  const Point3 dir_b(std::cos(alpha), std::sin(alpha), 0);
  OutputMesh out;
  const int c = out.add_point(Point3(0, 0, 0), 0, PointKind::Corner);
  const int a1 = out.add_point(Point3(1, 0, 0), 0, PointKind::Line);
  const int a2 = out.add_point(Point3(2, 0, 0), 0, PointKind::Line);
  const int b1 = out.add_point(dir_b, 0, PointKind::Line);
  const int b2 = out.add_point(dir_b * 2.0, 0, PointKind::Line);
  out.faces = {{c, a1, b1}, {b1, a1, a2}, {b2, b1, a2}};
  out.face_patch = {0, 0, 0};
  LinePath b;
  b.polyline = {Point3(0, 0, 0), dir_b * 0.7, dir_b * 3.0};
  b.segment_host = {5, 6};
  b.points = {c, b1, b2};
  b.arc = {0.0, 1.0, 2.0};
  b.slidable = {0, 1, 0};
  std::vector<LinePath> paths{b};
  auto worst = [&] { return worst_degrees(out); };
  auto worst_beyond_tip = [&] {
    double w = 1e9;
    for (size_t f = 1; f < out.faces.size(); ++f) w = std::min(w, min_angle(out.points, out.faces[f]));
    return w * 180.0 / 3.14159265358979323846;
  };
  const std::vector<std::array<int, 2>> lines{{c, a1}, {a1, a2}, {c, b1}, {b1, b2}};
  EXPECT_NEAR(worst(), 17.4, 0.1);
  {
    // With the first point of B at 1.15 the faces beyond the tip have 22.6 degrees and the tip's
    // 19.3 is the ring's smallest. Not told the lines (as before stop 41), no slide can raise
    // that, and nothing moves; told them, the point slides and the faces beyond pass 30.
    OutputMesh at_115 = out;
    at_115.points[b1] = dir_b * 1.15;
    std::vector<LinePath> paths_115 = paths;
    paths_115[0].arc[1] = 1.15;
    OutputMesh unaware = at_115;
    std::vector<LinePath> unaware_paths = paths_115;
    auto beyond = [](const OutputMesh& m) {
      double w = 1e9;
      for (size_t f = 1; f < m.faces.size(); ++f) w = std::min(w, min_angle(m.points, m.faces[f]));
      return w * 180.0 / 3.14159265358979323846;
    };
    EXPECT_NEAR(beyond(at_115), 22.57, 0.01);
    EXPECT_TRUE(slide_line_points(unaware, unaware_paths, {}, 30.0 * 3.14159265358979323846 / 180.0, 0.0).empty());
    EXPECT_EQ(slide_line_points(at_115, paths_115, lines, 30.0 * 3.14159265358979323846 / 180.0, 0.0).size(), 1u);
    EXPECT_GE(beyond(at_115), 30.0);
    EXPECT_NEAR(min_angle(at_115.points, at_115.faces[0]) * 180.0 / 3.14159265358979323846, 19.3, 1e-9);
  }
  {
    // Between the two bounds (15 and 20 degrees here: the ring's 17.4 lies between them) a slide
    // must reach the goal. The tip's 19.3 stays the ring's smallest wherever the point goes, so
    // no place reaches 20 and nothing moves; a goal of 19 is reached.
    const double deg = 3.14159265358979323846 / 180.0;
    OutputMesh copy = out;
    std::vector<LinePath> copy_paths = paths;
    EXPECT_TRUE(slide_line_points(copy, copy_paths, lines, 15.0 * deg, 20.0 * deg).empty());
    EXPECT_EQ(copy.points[b1], out.points[b1]);
    EXPECT_EQ(slide_line_points(copy, copy_paths, lines, 15.0 * deg, 19.0 * deg).size(), 1u);
  }
  EXPECT_EQ(slide_line_points(out, paths, lines, 30.0 * 3.14159265358979323846 / 180.0, 0.0).size(), 1u);
  EXPECT_NEAR(worst(), 19.3, 1e-6);  // the tip
  EXPECT_GE(worst_beyond_tip(), 30.0);  // measured 30.7
  EXPECT_NEAR((out.points[b1] ^ dir_b).Norm(), 0.0, 1e-12);  // still on line B
  EXPECT_NEAR(out.points[b1].Norm(), paths[0].arc[1], 1e-12);
  EXPECT_GT(paths[0].arc[1], 1.0);
  EXPECT_LT(paths[0].arc[1], 2.0);
  EXPECT_EQ(out.host[b1], 6);
  EXPECT_EQ(out.points[a1], Point3(1, 0, 0));  // line A's points were not in the path: they stay
  // Nothing below the threshold: nothing moves.
  EXPECT_TRUE(slide_line_points(out, paths, lines, 5.0 * 3.14159265358979323846 / 180.0, 0.0).empty());
}

namespace {

// A straight line from (0, 0) to (2, 0), corners at its ends and its one slidable point at 1,
// with a free point on each side of it: four faces, all around the line point.
struct StraightLineBetweenTwoFreePoints {
  StraightLineBetweenTwoFreePoints(const Point3& above, const Point3& below) {
    b0 = out.add_point(Point3(0, 0, 0), 0, PointKind::Corner);
    b1 = out.add_point(Point3(1, 0, 0), 0, PointKind::Line);
    b2 = out.add_point(Point3(2, 0, 0), 0, PointKind::Corner);
    const int a = out.add_point(above, 0, PointKind::Free);
    const int b = out.add_point(below, 0, PointKind::Free);
    out.faces = {{b0, b1, a}, {b1, b2, a}, {b1, b0, b}, {b2, b1, b}};
    out.face_patch = {0, 0, 1, 1};
    LinePath line;
    line.polyline = {Point3(0, 0, 0), Point3(2, 0, 0)};
    line.segment_host = {3};
    line.points = {b0, b1, b2};
    line.arc = {0.0, 1.0, 2.0};
    line.slidable = {0, 1, 0};
    paths = {line};
    lines = {{b0, b1}, {b1, b2}};
  }
  double worst_degrees() const { return ::worst_degrees(out); }
  OutputMesh out;
  int b0 = -1, b1 = -1, b2 = -1;
  std::vector<LinePath> paths;
  std::vector<std::array<int, 2>> lines;
};

}  // namespace

TEST(RemeshPieces, LinePointTakesASmallStepWhereNoneOfTheUsualPlacesReachesTheGoal) {
  // The faces around the point have 29.37 degrees where it is and at most that at the nine
  // places a slide tries first (sixths and twelfths of the arc), but 30.95 a 48th of the arc
  // back (x = 0.958). Between the bounds (25 and 30 degrees) a slide must reach the goal: only
  // that step does.
  const double deg = 3.14159265358979323846 / 180.0;
  StraightLineBetweenTwoFreePoints m(Point3(0.63, 1.42, 0), Point3(1.25, -1.29, 0));
  EXPECT_NEAR(m.worst_degrees(), 29.37, 0.01);
  EXPECT_EQ(slide_line_points(m.out, m.paths, m.lines, 25.0 * deg, 30.0 * deg).size(), 1u);
  EXPECT_NEAR(m.out.points[m.b1].X(), 2.0 * (0.5 - 1.0 / 48), 1e-12);
  EXPECT_EQ(m.out.points[m.b1].Y(), 0.0);
  EXPECT_NEAR(m.paths[0].arc[1], m.out.points[m.b1].X(), 1e-12);
  EXPECT_NEAR(m.worst_degrees(), 30.95, 0.01);
}

TEST(RemeshPieces, LinePointTakesTheBestGainShortOfTheGoalOnlyWhenAskedTo) {
  // The faces around the point have 25.62 degrees, between the bounds (25 and 30), and no place
  // a slide tries reaches 30. A plain sweep leaves the point where it is; asked for the best
  // gain short of the goal, the point takes it: of the small steps beside it, x = 1.0417 is the
  // first to gain half a degree (26.97) and x = 1.0833, tried after it, gains most (27.47, less
  // than half a degree above the first: a rule counting each gain from the last one found took
  // the first).
  const double deg = 3.14159265358979323846 / 180.0;
  StraightLineBetweenTwoFreePoints m(Point3(0.7, 1.41, 0), Point3(1.49, -1.64, 0));
  EXPECT_NEAR(m.worst_degrees(), 25.62, 0.01);
  EXPECT_TRUE(slide_line_points(m.out, m.paths, m.lines, 25.0 * deg, 30.0 * deg).empty());
  EXPECT_EQ(m.out.points[m.b1], Point3(1, 0, 0));
  EXPECT_EQ(slide_line_points(m.out, m.paths, m.lines, 25.0 * deg, 30.0 * deg, true).size(), 1u);
  EXPECT_NEAR(m.out.points[m.b1].X(), 2.0 * (0.5 + 2.0 / 48), 1e-12);
  EXPECT_NEAR(m.worst_degrees(), 27.47, 0.01);
  EXPECT_EQ(m.out.points[m.b1].Y(), 0.0);
  EXPECT_NEAR(m.paths[0].arc[1], m.out.points[m.b1].X(), 1e-12);
  // At the best place tried already: a second sweep finds no gain of half a degree.
  EXPECT_TRUE(slide_line_points(m.out, m.paths, m.lines, 25.0 * deg, 30.0 * deg, true).empty());
}

TEST(RemeshPieces, TwoLinePointsTakeTheBestGainShortOfTheGoalTogether) {
  // Two parallel lines 0.51 apart, y = 0 and y = 0.51 from x = 0 to 2, each with one slidable
  // point (at 0.94 and 1.05) facing the other across the strip, and a free point beyond each
  // line: every face has one of the two points, whose rings have 25.69 degrees. No slide of
  // either alone reaches 30 or gains half a degree, and no pair reaches 30, so a plain sweep
  // leaves them; asked for the best gain short of the goal, they slide together (27.02 at the
  // best pair of places) and stay on their lines.
  const double deg = 3.14159265358979323846 / 180.0;
  OutputMesh out;
  const int a0 = out.add_point(Point3(0, 0, 0), 0, PointKind::Corner);
  const int a1 = out.add_point(Point3(0.94, 0, 0), 0, PointKind::Line);
  const int a2 = out.add_point(Point3(2, 0, 0), 0, PointKind::Corner);
  const int b0 = out.add_point(Point3(0, 0.51, 0), 0, PointKind::Corner);
  const int b1 = out.add_point(Point3(1.05, 0.51, 0), 0, PointKind::Line);
  const int b2 = out.add_point(Point3(2, 0.51, 0), 0, PointKind::Corner);
  const int below = out.add_point(Point3(0.64, -1.31, 0), 0, PointKind::Free);
  const int above = out.add_point(Point3(1.47, 1.79, 0), 0, PointKind::Free);
  out.faces = {{a0, a1, b1}, {a0, b1, b0}, {a1, a2, b2}, {a1, b2, b1},
               {a1, a0, below}, {a2, a1, below}, {b0, b1, above}, {b1, b2, above}};
  out.face_patch = {0, 0, 0, 0, 1, 1, 2, 2};
  EXPECT_NEAR(worst_degrees(out), 25.69, 0.01);
  auto line = [](Point3 from, Point3 to, std::array<int, 3> points, double arc) {
    LinePath path;
    path.polyline = {from, to};
    path.segment_host = {0};
    path.points = {points[0], points[1], points[2]};
    path.arc = {0.0, arc, 2.0};
    path.slidable = {0, 1, 0};
    return path;
  };
  std::vector<LinePath> paths{line(Point3(0, 0, 0), Point3(2, 0, 0), {a0, a1, a2}, 0.94),
                              line(Point3(0, 0.51, 0), Point3(2, 0.51, 0), {b0, b1, b2}, 1.05)};
  const std::vector<std::array<int, 2>> lines{{a0, a1}, {a1, a2}, {b0, b1}, {b1, b2}};
  EXPECT_TRUE(slide_line_points(out, paths, lines, 25.0 * deg, 30.0 * deg).empty());
  EXPECT_EQ(out.points[a1], Point3(0.94, 0, 0));
  EXPECT_EQ(out.points[b1], Point3(1.05, 0.51, 0));
  const std::vector<int> moved = slide_line_points(out, paths, lines, 25.0 * deg, 30.0 * deg, true);
  EXPECT_EQ(moved, (std::vector<int>{a1, b1}));
  EXPECT_NEAR(worst_degrees(out), 27.02, 0.01);
  EXPECT_EQ(out.points[a1].Y(), 0.0);
  EXPECT_EQ(out.points[b1].Y(), 0.51);
  EXPECT_NEAR(paths[0].arc[1], out.points[a1].X(), 1e-12);
  EXPECT_NEAR(paths[1].arc[1], out.points[b1].X(), 1e-12);
}

TEST(RemeshPieces, StripLineTakesThePointsAcrossShiftedAlongTheOtherSide) {
  // A line of 10 elements along x, the other side of the strip 0.01 away with points at 0.28,
  // 1.28, ... 5.28 (its segments end at x = 6): the points land there, the rest of the line
  // (4.72 elements) is filled evenly, a point out of reach is ignored.
  const std::vector<Point3> polyline{Point3(0, 0, 0), Point3(4, 0, 0), Point3(10, 0, 0)};
  const std::vector<double> cumulative{0.0, 4.0, 10.0};
  std::vector<Point3> opposite;
  for (int k = 0; k < 6; ++k) opposite.push_back(Point3(k + 0.28, 0.01, 0));
  opposite.push_back(Point3(8.5, 1.0, 0));  // far from the line
  const std::vector<double> at = staggered_positions(polyline, cumulative, opposite, 0.1);
  ASSERT_EQ(at.size(), 12u);
  EXPECT_EQ(at.front(), 0.0);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(at[1 + k], k + 0.28, 1e-12);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(at[7 + k], 5.28 + (k + 1) * 4.72 / 5, 1e-12);
  EXPECT_EQ(at.back(), 10.0);
  EXPECT_TRUE(staggered_positions(polyline, cumulative, {Point3(5, 1, 0)}, 0.1).empty());
}

// A point whose host face is degenerate (a scan's zero-area face; here the only face around its
// corners, so their averaged normals are zero too) has no barycentric coordinates: quadratic and
// cubic recovery leave it where it is instead of writing NaN.
TEST(RemeshPieces, RecoveryLeavesPointsOnDegenerateHostFacesAsTheyAre) {
  // Face 0 has two equal corners, face 2 three collinear ones.
  const Surface s = Surface::from_arrays({Point3(0, 0, 0), Point3(0, 0, 0), Point3(2, 0, 0), Point3(1, 0, 0),
                                          Point3(5, 5, 0), Point3(6, 5, 0), Point3(5, 6, 0)},
                                         {{0, 1, 2}, {4, 5, 6}, {0, 3, 2}}, {});
  for (Recovery mode : {Recovery::Quadratic, Recovery::Cubic}) {
    for (int host : {0, 2}) {
      OutputMesh out;
      const int on_degenerate = out.add_point(Point3(0.5, 0, 0), host, PointKind::Free);
      const int on_good = out.add_point(Point3(5.2, 5.2, 0), 1, PointKind::Free);
      recover_surface(out, s, mode);
      EXPECT_EQ(out.points[on_degenerate], Point3(0.5, 0, 0));
      for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(out.points[on_good][k]));
      EXPECT_NEAR(out.points[on_good][2], 0.0, 1e-12);  // a flat face: recovery keeps the plane
    }
  }
}

TEST(RemeshPieces, PointGridFindsTheSameCellsForSmallAndHugeRadii) {
  // Points on a 10 x 10 x 10 lattice of spacing 1 in cells of 1: small radii walk the box of
  // cells, radii whose box outnumbers the filled cells visit the filled cells; both give every
  // point within the box of cells around the query, and no other.
  PointGrid grid(1.0);
  std::vector<Point3> points;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 10; ++k) {
        points.emplace_back(i + 0.5, j + 0.5, k + 0.5);
        grid.add(int(points.size()) - 1, points.back());
      }
  const Point3 q(3.2, 4.7, 5.1);
  for (double r : {0.5, 1.5, 2.5, 6.0, 40.0, 1e6}) {
    std::vector<int> found;
    grid.for_each_near(q, r, [&](int id) { found.push_back(id); });
    std::sort(found.begin(), found.end());
    const long n = long(std::ceil(r));
    std::vector<int> expected;
    for (size_t v = 0; v < points.size(); ++v) {
      bool in = true;
      for (int c = 0; c < 3; ++c) in = in && std::abs(long(std::floor(points[v][c])) - long(std::floor(q[c]))) <= n;
      if (in) expected.push_back(int(v));
    }
    EXPECT_EQ(found, expected) << "radius " << r;
  }
}

// A line that is one long input edge, its size 0.05 at one end and 0.5 at the other: its points
// follow the size along the edge (segments growing by one ratio, the first about 0.065 long), not
// evenly spaced as before, when a corner's small size only changed how many segments there were.
TEST(RemeshPieces, LinePointsFollowTheSizeAlongOneLongInputEdge) {
  TriMesh m;
  test::build(m, {Point3(0, 0, 0), Point3(1, 0, 0), Point3(1, 0.2, 0), Point3(0, 0.2, 0)}, {{0, 1, 2}, {0, 2, 3}});
  const features::Result fr = features::detect(m, features::Params{});
  ASSERT_EQ(fr.corners.size(), 4u);
  const Surface s = Surface::from_mesh(m, fr.patch_of_face);
  const SizeField size(s, std::vector<double>{0.05, 0.5, 0.5, 0.5});
  OutputMesh out;
  discretise_features(m, fr, s, size, out);
  std::vector<double> xs;  // the points on the edge y = 0, in order
  for (const Point3& p : out.points)
    if (std::fabs(p[1]) < 1e-12) xs.push_back(p[0]);
  std::sort(xs.begin(), xs.end());
  // Integral of 1/h: ln(10) / 0.45 = 5.1 -> 5 segments, each 10^(1/5) x the one before.
  ASSERT_EQ(xs.size(), 6u);
  EXPECT_NEAR(xs[1], (std::pow(10.0, 0.2) - 1) / 9, 1e-9);
  for (size_t k = 1; k + 1 < xs.size(); ++k)
    EXPECT_NEAR((xs[k + 1] - xs[k]) / (xs[k] - xs[k - 1]), std::pow(10.0, 0.2), 1e-9) << k;
  // Where the size is the same at both ends the points stay evenly spaced: the edge y = 0.2,
  // 1 long between two sizes of 0.5, gets two segments.
  std::vector<double> top;
  for (const Point3& p : out.points)
    if (std::fabs(p[1] - 0.2) < 1e-12) top.push_back(p[0]);
  std::sort(top.begin(), top.end());
  ASSERT_EQ(top.size(), 3u);
  EXPECT_NEAR(top[1], 0.5, 1e-12);
}
