// Face corners between two feature edges under 30 degrees, one face filling the wedge, are
// measured apart: the lines bound them. Every other corner counts towards the angle off wedges.
#include "remesh/mesh_measures.h"

#include <cmath>

#include <gtest/gtest.h>

using namespace mr;
using namespace mr::remesh;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180;

// A fan at the origin in the plane z = 0: rays at the given angles (degrees), one face
// between each pair of neighbouring rays.
OutputMesh fan(const std::vector<double>& rays) {
  OutputMesh out;
  out.add_point(Point3(0, 0, 0), 0, PointKind::Corner);
  for (double a : rays) out.add_point(Point3(std::cos(a * kDeg), std::sin(a * kDeg), 0), 0, PointKind::Line);
  for (int k = 1; k < int(rays.size()); ++k) {
    out.faces.push_back({0, k, k + 1});
    out.face_patch.push_back(0);
  }
  return out;
}

}  // namespace

TEST(WedgeMeasure, ANarrowWedgeBetweenTwoLinesIsMeasuredApart) {
  // Rays at 0, 12 and 80 degrees; lines along the first two: the 12-degree face is a wedge tip.
  const OutputMesh out = fan({0, 12, 80});
  const WedgeMeasure w = measure_wedges(out, {{0, 1}, {0, 2}});
  EXPECT_EQ(w.wedge_tips, 1);
  EXPECT_NEAR(w.min_wedge_angle_deg, 12.0, 1e-9);
  // Off the tip: the isosceles faces' base angles (84 and 56 degrees) and the 68-degree corner.
  EXPECT_NEAR(w.min_angle_off_wedges_deg, 56.0, 1e-9);
}

TEST(WedgeMeasure, AWedgeSplitIntoTwoFacesOrWithoutLinesIsNoTip) {
  // The same 12 degrees split by a free ray at 6: neither face fills the wedge alone, so the
  // 6-degree corners count as faults of the mesh, not of the lines.
  const OutputMesh split = fan({0, 6, 12});
  const WedgeMeasure w = measure_wedges(split, {{0, 1}, {0, 3}});
  EXPECT_EQ(w.wedge_tips, 0);
  EXPECT_NEAR(w.min_angle_off_wedges_deg, 6.0, 1e-9);
  // One face of 12 degrees with a line on one side only: no wedge either.
  const WedgeMeasure one_line = measure_wedges(fan({0, 12}), {{0, 1}});
  EXPECT_EQ(one_line.wedge_tips, 0);
  EXPECT_NEAR(one_line.min_angle_off_wedges_deg, 12.0, 1e-9);
  // Two lines 40 degrees apart: wider than the bound, an ordinary corner.
  const WedgeMeasure wide = measure_wedges(fan({0, 40}), {{0, 1}, {0, 2}});
  EXPECT_EQ(wide.wedge_tips, 0);
  EXPECT_NEAR(wide.min_angle_off_wedges_deg, 40.0, 1e-9);
}
