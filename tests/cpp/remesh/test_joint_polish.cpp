// The joint search around faces under the goal. A one-layer strip between two straight lines, a
// few hundredths wide, with the points of both lines spaced unevenly: the slides of single
// points and of pairs leave faces under 30 degrees, moving the points around them together
// lifts them. The points stay on their lines (and free points on the input), in order, and
// where the goal is out of reach nothing moves.
#include "remesh/joint_polish.h"
#include "remesh/line_sliding.h"
#include "remesh/triangle_geometry.h"
#include "output_lattice.h"
#include "unit_square.h"

#include <gtest/gtest.h>

using namespace mr;
using namespace mr::remesh;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

double worst_degrees(const OutputMesh& out) { return test::worst_angle(out) / kDeg; }

// Lines y = 0.45 and y = 0.45 + width from x = 0 to 1 on the unit square, corners at their
// ends, the points at `bottom` and `top` (x, first 0 and last 1), the strip between them
// zipped by x. Nothing else is meshed.
struct Strip {
  Strip(const test::UnitSquare& sq, double width, const std::vector<double>& bottom, const std::vector<double>& top) {
    auto host = [&](const Point3& p) { return sq.locator.locate(p, -1, Point3(0, 0, 1), -1, 0.2).face; };
    const double y[2] = {0.45, 0.45 + width};
    const std::vector<double>* xs[2] = {&bottom, &top};
    std::vector<int> ids[2];
    paths.resize(2);
    for (int l = 0; l < 2; ++l) {
      LinePath& path = paths[size_t(l)];
      path.polyline = {Point3(0, y[l], 0), Point3(1, y[l], 0)};
      path.segment_host = {host(Point3(0.5, y[l], 0))};
      for (size_t k = 0; k < xs[l]->size(); ++k) {
        const Point3 p((*xs[l])[k], y[l], 0);
        const bool end = k == 0 || k + 1 == xs[l]->size();
        ids[l].push_back(out.add_point(p, host(p), end ? PointKind::Corner : PointKind::Line));
        path.slidable.push_back(!end);
      }
      path.points = ids[l];
      path.arc = *xs[l];
      for (size_t k = 0; k + 1 < ids[l].size(); ++k) lines.push_back({ids[l][k], ids[l][k + 1]});
    }
    const std::vector<int>&b = ids[0], &t = ids[1];
    size_t i = 0, j = 0;
    while (i + 1 < b.size() || j + 1 < t.size()) {
      if (j + 1 >= t.size() || (i + 1 < b.size() && bottom[i + 1] <= top[j + 1])) {
        out.faces.push_back({b[i], b[i + 1], t[j]});
        ++i;
      } else {
        out.faces.push_back({b[i], t[j + 1], t[j]});
        ++j;
      }
    }
    out.face_patch.assign(out.faces.size(), 0);
  }
  /// The slides of the post-pass before the joint search: plain sweeps, then gains short of the goal.
  void slide() {
    for (int it = 0; it < 5 && !slide_line_points(out, paths, lines, 25 * kDeg, 30 * kDeg).empty(); ++it) {}
    for (int it = 0; it < 5 && !slide_line_points(out, paths, lines, 25 * kDeg, 30 * kDeg, true).empty(); ++it) {}
  }
  OutputMesh out;
  std::vector<LinePath> paths;
  std::vector<std::array<int, 2>> lines;
};

const std::vector<double> kBottom{0.000, 0.098, 0.204, 0.293, 0.419, 0.493, 0.580, 0.717, 0.782, 0.888, 1.000};
const std::vector<double> kTop{0.000, 0.028, 0.138, 0.234, 0.373, 0.450, 0.547, 0.631, 0.756, 0.865, 0.924, 1.000};

}  // namespace

TEST(RemeshJointPolish, StripFacesTheSlidesLeaveUnderTheGoalReachItWhenPointsMoveTogether) {
  test::UnitSquare sq(0.1);
  Strip s(sq, 0.0341, kBottom, kTop);
  EXPECT_LT(worst_degrees(s.out), 25.0);
  s.slide();
  const double after_slides = worst_degrees(s.out);
  EXPECT_GT(after_slides, 25.0);
  EXPECT_LT(after_slides, 29.5);  // measured 26.5
  const OutputMesh before = s.out;
  const std::vector<int> moved = polish_jointly(s.out, s.paths, s.lines, sq.locator, {}, 30 * kDeg);
  EXPECT_FALSE(moved.empty());
  EXPECT_GE(worst_degrees(s.out), 30.0);
  for (const LinePath& path : s.paths) {
    const double y = path.polyline[0].Y();
    for (size_t k = 0; k < path.points.size(); ++k) {
      const Point3& p = s.out.points[size_t(path.points[k])];
      EXPECT_NEAR(p.Y(), y, 1e-15);  // on its line
      EXPECT_NEAR(p.Z(), 0.0, 1e-15);
      EXPECT_NEAR(path.arc[k], p.X(), 1e-12);
      if (k > 0) {
        EXPECT_GT(path.arc[k], path.arc[k - 1]);  // in order
      }
      if (!path.slidable[k]) {
        EXPECT_EQ(p, before.points[size_t(path.points[k])]);
      }
      EXPECT_GE(s.out.host[size_t(path.points[k])], 0);
    }
  }
  for (int v : moved) EXPECT_FALSE(s.out.points[size_t(v)] == before.points[size_t(v)]);
  // Again: nothing is under the goal any more.
  EXPECT_TRUE(polish_jointly(s.out, s.paths, s.lines, sq.locator, {}, 30 * kDeg).empty());
}

TEST(RemeshJointPolish, NothingMovesWhereNoFaceIsUnderTheGoalOrItIsOutOfReach) {
  test::UnitSquare sq(0.1);
  std::vector<double> even_bottom, staggered_top{0.0};
  for (int k = 0; k <= 10; ++k) even_bottom.push_back(0.1 * k);
  for (int k = 0; k < 10; ++k) staggered_top.push_back(0.1 * k + 0.05);
  staggered_top.push_back(1.0);
  {  // Staggered over a width of 0.04: every face has 38.7 degrees or more.
    Strip s(sq, 0.04, even_bottom, staggered_top);
    ASSERT_GE(worst_degrees(s.out), 30.0);
    const OutputMesh before = s.out;
    EXPECT_TRUE(polish_jointly(s.out, s.paths, s.lines, sq.locator, {}, 30 * kDeg).empty());
    EXPECT_EQ(s.out.points, before.points);
  }
  {  // 0.005 wide: no places along the lines give a face at the ends 30 degrees.
    Strip s(sq, 0.005, even_bottom, staggered_top);
    const OutputMesh before = s.out;
    const std::vector<LinePath> paths = s.paths;
    EXPECT_TRUE(polish_jointly(s.out, s.paths, s.lines, sq.locator, {}, 30 * kDeg).empty());
    EXPECT_EQ(s.out.points, before.points);
    EXPECT_EQ(s.out.host, before.host);
    for (size_t l = 0; l < paths.size(); ++l) EXPECT_EQ(s.paths[l].arc, paths[l].arc);
  }
}

TEST(RemeshJointPolish, FreePointsMoveOnTheInputAndOnlyWhereMovable) {
  // The lattice with the free point (5, 1) pushed to 0.03 above the border's line points (no
  // line paths: the border stays): its faces have 10 degrees.
  test::UnitSquare sq(0.1);
  OutputMesh out = test::unit_lattice(sq.locator);
  const int v = test::lattice_id(5, 1);
  out.points[size_t(v)] = Point3(0.5, 0.03, 0);
  out.host[size_t(v)] = sq.locator.locate(out.points[size_t(v)], -1, Point3(0, 0, 1), -1, 0.2).face;
  const OutputMesh before = out;
  std::vector<LinePath> none;
  EXPECT_TRUE(polish_jointly(out, none, {}, sq.locator, std::vector<char>(out.points.size(), 0), 30 * kDeg).empty());
  EXPECT_EQ(out.points, before.points);
  std::vector<char> movable(out.points.size(), 0);
  movable[size_t(v)] = 1;
  EXPECT_EQ(polish_jointly(out, none, {}, sq.locator, movable, 30 * kDeg), std::vector<int>{v});
  EXPECT_GE(worst_degrees(out), 30.0);
  EXPECT_EQ(out.points[size_t(v)].Z(), 0.0);  // on the input
  EXPECT_LE((out.points[size_t(v)] - before.points[size_t(v)]).Norm(), 0.5 * 0.1 * 1.5);  // within its reach
  EXPECT_GE(out.host[size_t(v)], 0);
  for (size_t x = 0; x < out.points.size(); ++x) {
    if (int(x) != v) {
      EXPECT_EQ(out.points[x], before.points[x]);
    }
  }
}
