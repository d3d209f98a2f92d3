// The post-pass's search for better places of pinched free points, on a flat lattice: a free
// point pushed towards the border leaves faces of 10 degrees beside the border's line points; the
// search must lift them past the goal, keep the point on the input and every point it may not
// move where it is, and leave alone what is not movable or already at the goal.
#include "remesh/angle_smoothing.h"
#include "remesh/face_rings.h"
#include "remesh/star_shape.h"
#include "output_lattice.h"
#include "unit_square.h"

#include <gtest/gtest.h>

using namespace mr;
using namespace mr::remesh;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// The lattice with point (5, 1) pushed to 0.03 above the border y = 0.
OutputMesh pinched_lattice(const SurfaceLocator& locator, int& v) {
  OutputMesh out = test::unit_lattice(locator);
  v = test::lattice_id(5, 1);
  out.points[v] = Point3(0.5, 0.03, 0);
  out.host[v] = locator.locate(out.points[v], -1, Point3(0, 0, 1), -1, 0.2).face;
  return out;
}

double star_min(const OutputMesh& out, int v) {
  return star_min_angle(out.points, out.faces, FaceRings(out.points.size(), out.faces), v);
}

}  // namespace

TEST(RemeshAngleSmoothing, PinchedFreePointMovesToWhereItsFacesPassTheGoal) {
  test::UnitSquare sq(0.1);
  int v = -1;
  OutputMesh out = pinched_lattice(sq.locator, v);
  const OutputMesh before = out;
  ASSERT_NEAR(star_min(out, v) / kDeg, 10.01, 0.01);
  std::vector<char> movable(out.points.size(), 0);  // (its free neighbours, pinched too, stay)
  movable[size_t(v)] = 1;
  EXPECT_EQ(raise_pinched_free_points(out, sq.locator, movable, 30 * kDeg), std::vector<int>{v});
  EXPECT_GE(star_min(out, v), 30 * kDeg);
  EXPECT_GE(test::worst_angle(out), test::worst_angle(before));
  EXPECT_NEAR(out.points[v][2], 0.0, 1e-12);  // on the input
  EXPECT_GT(out.points[v][1], 0.03);          // away from the border's line points
  EXPECT_GE(out.host[v], 0);
  for (size_t x = 0; x < out.points.size(); ++x)
    if (int(x) != v) {
      EXPECT_EQ(out.points[x], before.points[x]);
    }
}

TEST(RemeshAngleSmoothing, PointsNotMovableOrAtTheGoalStay) {
  test::UnitSquare sq(0.1);
  int v = -1;
  OutputMesh out = pinched_lattice(sq.locator, v);
  const OutputMesh before = out;
  std::vector<char> movable(out.points.size(), 0);
  EXPECT_TRUE(raise_pinched_free_points(out, sq.locator, movable, 30 * kDeg).empty());
  // Movable, but its 10.01 degrees are above a goal of 9: nothing to raise.
  movable[size_t(v)] = 1;
  EXPECT_TRUE(raise_pinched_free_points(out, sq.locator, movable, 9 * kDeg).empty());
  // The untouched lattice (45 degrees everywhere) has nothing under 30.
  OutputMesh plain = test::unit_lattice(sq.locator);
  movable.assign(out.points.size(), 1);
  EXPECT_TRUE(raise_pinched_free_points(plain, sq.locator, movable, 30 * kDeg).empty());
  for (size_t x = 0; x < out.points.size(); ++x) EXPECT_EQ(out.points[x], before.points[x]);
}
