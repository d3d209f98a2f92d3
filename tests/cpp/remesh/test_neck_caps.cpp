// Neck caps: line points closer than 0.15 x target to another line (0.45 x target between two
// lines the caller gave) get caps of 1.7 x that distance (never below 0.05 x target, 0.01 x
// target between two given lines); lines farther apart get none, and neither do two lines that
// end at one corner (a wedge) nor one or two points where two lines touch in passing.
#include "remesh/neck_caps.h"

#include "shapes.h"

#include <gtest/gtest.h>

#include <vector>

using namespace mr;

namespace {

// Line points only: cap_necks reads the points and the lines, not the faces.
remesh::Surface points_only(const std::vector<Point3>& points) {
  return remesh::Surface::from_arrays(points, {{0, 1, 2}}, {});
}

// Two open lines of `n` + 1 points each along x from 0 to 1: the first at y = 0, the second at
// y = `gap`, or, with `shared_start`, from the first one's start point rising to `gap` at x = 1.
void two_lines(double gap, int n, bool shared_start, std::vector<Point3>& points,
               std::vector<features::DiscreteLine>& lines) {
  points.clear();
  lines.assign(2, {});
  for (int k = 0; k <= n; ++k) {
    lines[0].vertices.push_back(int(points.size()));
    points.emplace_back(double(k) / n, 0, 0);
  }
  for (int k = 0; k <= n; ++k) {
    if (k == 0 && shared_start) {
      lines[1].vertices.push_back(0);
      continue;
    }
    lines[1].vertices.push_back(int(points.size()));
    const double x = double(k) / n;
    points.emplace_back(x, shared_start ? gap * x : gap, 0);
  }
}

// No line given by the caller: every line was found by its dihedral angle.
std::vector<char> none(const std::vector<features::DiscreteLine>& lines) { return std::vector<char>(lines.size(), 0); }

}  // namespace

TEST(RemeshNeckCaps, LinesCloserThanTheNeckReachAreCappedAtTheirDistance) {
  std::vector<Point3> points;
  std::vector<features::DiscreteLine> lines;
  const double target = 0.1;
  two_lines(0.004, 10, false, points, lines);
  const remesh::Surface s = points_only(points);
  std::vector<double> cap(points.size(), 0.0);
  EXPECT_EQ(remesh::cap_necks(s, lines, none(lines), target, cap), 22);
  for (double c : cap) EXPECT_NEAR(c, 1.7 * 0.004, 1e-12);
}

TEST(RemeshNeckCaps, LinesFartherApartGetNoCapAndVeryCloseOnesTheFloor) {
  std::vector<Point3> points;
  std::vector<features::DiscreteLine> lines;
  const double target = 0.1;
  two_lines(0.02, 10, false, points, lines);  // 0.2 x target
  std::vector<double> cap(points.size(), 0.0);
  EXPECT_EQ(remesh::cap_necks(points_only(points), lines, none(lines), target, cap), 0);
  for (double c : cap) EXPECT_EQ(c, 0.0);

  two_lines(0.001, 10, false, points, lines);  // 1.7 x 0.001 is under the floor of 0.05 x target
  cap.assign(points.size(), 0.0);
  EXPECT_EQ(remesh::cap_necks(points_only(points), lines, none(lines), target, cap), 22);
  for (double c : cap) EXPECT_NEAR(c, 0.05 * target, 1e-12);
}

TEST(RemeshNeckCaps, ExistingSmallerCapsStay) {
  std::vector<Point3> points;
  std::vector<features::DiscreteLine> lines;
  two_lines(0.004, 10, false, points, lines);
  std::vector<double> cap(points.size(), 0.0);
  cap[3] = 0.001;
  remesh::cap_necks(points_only(points), lines, none(lines), 0.1, cap);
  EXPECT_EQ(cap[3], 0.001);
  EXPECT_NEAR(cap[4], 1.7 * 0.004, 1e-12);
}

TEST(RemeshNeckCaps, LinesEndingAtOneCornerAreAWedgeAndGetNoCap) {
  // Both lines start at the origin and are 0.004 apart at x = 1 (a 0.23-degree wedge).
  std::vector<Point3> points;
  std::vector<features::DiscreteLine> lines;
  two_lines(0.004, 10, true, points, lines);
  std::vector<double> cap(points.size(), 0.0);
  EXPECT_EQ(remesh::cap_necks(points_only(points), lines, none(lines), 0.5, cap), 0);
  for (double c : cap) EXPECT_EQ(c, 0.0);
}

TEST(RemeshNeckCaps, TwoPointsTouchingAnotherLineAreNoNeckThreeAre) {
  // The second line stays 0.05 away (beyond 0.15 x target) but for points that come within
  // 0.004 of the first: one or two such points in a row are where two lines touch in passing.
  std::vector<Point3> points;
  std::vector<features::DiscreteLine> lines;
  two_lines(0.05, 10, false, points, lines);
  std::vector<double> cap(points.size(), 0.0);
  for (int close : {5, 6}) {
    points[size_t(lines[1].vertices[size_t(close)])][1] = 0.004;
    cap.assign(points.size(), 0.0);
    EXPECT_EQ(remesh::cap_necks(points_only(points), lines, none(lines), 0.1, cap), 0) << close;
  }
  // Three in a row make a neck: those, and the first line's points across from them.
  points[size_t(lines[1].vertices[7])][1] = 0.004;
  cap.assign(points.size(), 0.0);
  EXPECT_GT(remesh::cap_necks(points_only(points), lines, none(lines), 0.1, cap), 3);
  for (int k : {5, 6, 7}) EXPECT_NEAR(cap[size_t(lines[1].vertices[size_t(k)])], 1.7 * 0.004, 1e-12) << k;
  EXPECT_NEAR(cap[size_t(lines[0].vertices[6])], 1.7 * 0.004, 1e-12);
  EXPECT_EQ(cap[size_t(lines[1].vertices[2])], 0.0);
}

TEST(RemeshNeckCaps, AClosedLineCountsARunAcrossItsSeam) {
  // A closed loop whose last two and first points lie 0.004 from a straight line beside it:
  // consecutive along the loop, across its seam, they make a run of three.
  const std::vector<Point3> points = {{0.2, 0.004, 0}, {0.9, 0.3, 0}, {0.5, 0.9, 0}, {0.0, 0.5, 0},
                                      {0.0, 0.004, 0}, {0.1, 0.004, 0}, {-1, 0, 0},   {2, 0, 0}};
  std::vector<features::DiscreteLine> lines(2);
  lines[0].vertices = {0, 1, 2, 3, 4, 5};
  lines[0].closed = true;
  lines[1].vertices = {6, 7};
  std::vector<double> cap(points.size(), 0.0);
  EXPECT_EQ(remesh::cap_necks(points_only(points), lines, none(lines), 0.1, cap), 3);
  for (int v : {0, 4, 5}) EXPECT_NEAR(cap[size_t(v)], 1.7 * 0.004, 1e-12) << v;
}

namespace {

// Two open lines `gap` apart (two_lines, 10 segments), target 0.1: `count` points capped, each
// at `each` (0: none).
void expect_caps(double gap, const std::vector<char>& given, int count, double each) {
  std::vector<Point3> points;
  std::vector<features::DiscreteLine> lines;
  two_lines(gap, 10, false, points, lines);
  std::vector<double> cap(points.size(), 0.0);
  EXPECT_EQ(remesh::cap_necks(points_only(points), lines, given, 0.1, cap), count) << gap;
  for (double c : cap) EXPECT_NEAR(c, each, 1e-12) << gap;
}

}  // namespace

TEST(RemeshNeckCaps, TwoGivenLinesAreCappedFromAWiderReach) {
  // 0.3 x target apart: beyond the reach between found lines, within the one between given lines.
  expect_caps(0.03, {1, 0}, 0, 0.0);  // one given line is not enough
  expect_caps(0.03, {1, 1}, 22, 1.7 * 0.03);
  // 0.5 x target apart: beyond both reaches.
  expect_caps(0.05, {1, 1}, 0, 0.0);
}

TEST(RemeshNeckCaps, TwoGivenLinesHaveALowerFloor) {
  // 0.004 x target apart: 1.7 x that is under both floors. Found lines stop at 0.05 x target,
  // given ones at 0.01 x target; 0.02 x target apart, 1.7 x the width is above that.
  expect_caps(0.0004, {1, 0}, 22, 0.05 * 0.1);
  expect_caps(0.0004, {1, 1}, 22, 0.01 * 0.1);
  expect_caps(0.002, {1, 1}, 22, 1.7 * 0.002);
}

TEST(RemeshNeckCaps, ALineIsGivenWhenEveryEdgeOfItIsASelectedFaceEdge) {
  TriMesh m;
  test::grid(m, 2);  // 3 x 3 vertices, row by row
  std::vector<features::DiscreteLine> lines(3);
  lines[0].vertices = {0, 1, 2};  // bottom row: both edges selected below
  lines[1].vertices = {3, 4, 5};  // middle row: one edge selected
  lines[2].vertices = {6, 7, 8};  // top row: none
  auto select = [&](int a, int b) {
    for (auto& f : m.face)
      for (int z = 0; z < 3; ++z) {
        const int x = int(vcg::tri::Index(m, f.V(z))), y = int(vcg::tri::Index(m, f.V((z + 1) % 3)));
        if ((x == a && y == b) || (x == b && y == a)) f.SetFaceEdgeS(z);
      }
  };
  select(0, 1);
  select(1, 2);
  select(3, 4);
  EXPECT_EQ(remesh::given_lines(m, lines, true), (std::vector<char>{1, 0, 0}));
  EXPECT_EQ(remesh::given_lines(m, lines, false), (std::vector<char>{0, 0, 0}));
}
