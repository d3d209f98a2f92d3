// Neck caps: line points closer than 0.1 x target to another line get caps of 1.7 x that
// distance (never below 0.05 x target); lines farther apart get none, and neither do two lines
// that end at one corner (a wedge) nor a lone point where two lines touch in passing.
#include "remesh/neck_caps.h"

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

}  // namespace

TEST(RemeshNeckCaps, LinesCloserThanATenthOfTheTargetAreCappedAtTheirDistance) {
  std::vector<Point3> points;
  std::vector<features::DiscreteLine> lines;
  const double target = 0.1;
  two_lines(0.004, 10, false, points, lines);
  const remesh::Surface s = points_only(points);
  std::vector<double> cap(points.size(), 0.0);
  EXPECT_EQ(remesh::cap_necks(s, lines, target, cap), 22);
  for (double c : cap) EXPECT_NEAR(c, 1.7 * 0.004, 1e-12);
}

TEST(RemeshNeckCaps, LinesFartherApartGetNoCapAndVeryCloseOnesTheFloor) {
  std::vector<Point3> points;
  std::vector<features::DiscreteLine> lines;
  const double target = 0.1;
  two_lines(0.012, 10, false, points, lines);  // 0.12 x target
  std::vector<double> cap(points.size(), 0.0);
  EXPECT_EQ(remesh::cap_necks(points_only(points), lines, target, cap), 0);
  for (double c : cap) EXPECT_EQ(c, 0.0);

  two_lines(0.001, 10, false, points, lines);  // 1.7 x 0.001 is under the floor of 0.05 x target
  cap.assign(points.size(), 0.0);
  EXPECT_EQ(remesh::cap_necks(points_only(points), lines, target, cap), 22);
  for (double c : cap) EXPECT_NEAR(c, 0.05 * target, 1e-12);
}

TEST(RemeshNeckCaps, ExistingSmallerCapsStay) {
  std::vector<Point3> points;
  std::vector<features::DiscreteLine> lines;
  two_lines(0.004, 10, false, points, lines);
  std::vector<double> cap(points.size(), 0.0);
  cap[3] = 0.001;
  remesh::cap_necks(points_only(points), lines, 0.1, cap);
  EXPECT_EQ(cap[3], 0.001);
  EXPECT_NEAR(cap[4], 1.7 * 0.004, 1e-12);
}

TEST(RemeshNeckCaps, LinesEndingAtOneCornerAreAWedgeAndGetNoCap) {
  // Both lines start at the origin and are 0.004 apart at x = 1 (a 0.23-degree wedge).
  std::vector<Point3> points;
  std::vector<features::DiscreteLine> lines;
  two_lines(0.004, 10, true, points, lines);
  std::vector<double> cap(points.size(), 0.0);
  EXPECT_EQ(remesh::cap_necks(points_only(points), lines, 0.5, cap), 0);
  for (double c : cap) EXPECT_EQ(c, 0.0);
}

TEST(RemeshNeckCaps, ALonePointTouchingAnotherLineIsNoNeck) {
  // The second line stays 0.05 away (beyond 0.1 x target) but for one point that comes within
  // 0.004 of the first: only that point and its nearest point on the first line are close, each
  // without a close neighbour along its line.
  std::vector<Point3> points;
  std::vector<features::DiscreteLine> lines;
  two_lines(0.05, 10, false, points, lines);
  points[size_t(lines[1].vertices[5])][1] = 0.004;
  std::vector<double> cap(points.size(), 0.0);
  EXPECT_EQ(remesh::cap_necks(points_only(points), lines, 0.1, cap), 0);
  // Two neighbouring points that close make a neck: both, and the first line's points beside them.
  points[size_t(lines[1].vertices[6])][1] = 0.004;
  cap.assign(points.size(), 0.0);
  EXPECT_GT(remesh::cap_necks(points_only(points), lines, 0.1, cap), 0);
  EXPECT_NEAR(cap[size_t(lines[1].vertices[5])], 1.7 * 0.004, 1e-12);
  EXPECT_NEAR(cap[size_t(lines[1].vertices[6])], 1.7 * 0.004, 1e-12);
  EXPECT_EQ(cap[size_t(lines[1].vertices[2])], 0.0);
}

TEST(RemeshNeckCaps, AClosedLineCountsItsNeighboursAcrossItsSeam) {
  // A closed square loop whose last and first points lie 0.004 from a straight line beside it:
  // they are neighbours along the loop, so both are a neck.
  // Loop: starts at (0.2, 0.004), goes round, ends at (0.1, 0.004); the line runs along y = 0.
  const std::vector<Point3> points = {{0.2, 0.004, 0}, {0.9, 0.3, 0}, {0.5, 0.9, 0}, {0.0, 0.5, 0}, {0.1, 0.004, 0},
            {-1, 0, 0}, {2, 0, 0}};
  std::vector<features::DiscreteLine> lines(2);
  lines[0].vertices = {0, 1, 2, 3, 4};
  lines[0].closed = true;
  lines[1].vertices = {5, 6};
  std::vector<double> cap(points.size(), 0.0);
  EXPECT_EQ(remesh::cap_necks(points_only(points), lines, 0.1, cap), 2);
  EXPECT_NEAR(cap[0], 1.7 * 0.004, 1e-12);
  EXPECT_NEAR(cap[4], 1.7 * 0.004, 1e-12);
}
