// The count of slivers the union made and left (slivers_left.h): a face under the angle
// counts unless the input face it lies in was no better.
#include "shapes.h"
#include "union/slivers_left.h"
#include "union/triangle_angles.h"
#include "union_checks.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace mr;
using namespace mr::surface_union;

namespace {

constexpr double kDeg = 3.14159265358979323846 / 180;

// An isosceles triangle in the xy plane whose apex angle (its smallest) is `deg` degrees.
void add_needle(std::vector<std::array<double, 3>>& v, std::vector<std::array<int, 3>>& f, double deg, double x0) {
  const int base = int(v.size());
  const double h = 0.5 / std::tan(deg * kDeg / 2);
  v.push_back({x0, 0, 0});
  v.push_back({x0 + 1, 0, 0});
  v.push_back({x0 + 0.5, h, 0});
  f.push_back({base, base + 1, base + 2});
}

}  // namespace

TEST(SliversLeft, CountsFacesUnderTheAngleThatAreWorseThanTheirInputFace) {
  // Sources in all bodies' faces in order: 0 is the first body's 60 deg face, 1 the second
  // body's 2 deg needle.
  Body good, needle;
  add_needle(good.vertices, good.faces, 60, 0);
  add_needle(needle.vertices, needle.faces, 2, 10);
  const std::vector<Body> input = {good, needle};
  Result r;
  add_needle(r.vertices, r.faces, 1, 0);   // in the good face: counted
  add_needle(r.vertices, r.faces, 1, 2);   // in the needle, and worse: counted
  add_needle(r.vertices, r.faces, 3, 4);   // in the needle, better than it: the input's
  add_needle(r.vertices, r.faces, 30, 6);  // not a sliver
  add_needle(r.vertices, r.faces, 4, 8);   // without a source: counted
  r.face_source = {0, 1, 1, 0, -1};
  EXPECT_EQ(find_slivers_left(r, input, 5.0), (std::vector<int>{0, 1, 4}));
  EXPECT_TRUE(find_slivers_left(r, input, 0.5).empty());  // nothing under half a degree
}

TEST(SliversLeft, TheSliverStepLeavesNoneOfTheCutsSliversOnThreeSpheres) {
  auto sphere = [](int n, double dx, double dy, double dz, double s) {
    TriMesh m;
    test::sphere(m, n);
    return test::make_body(m, dx, dy, dz, s);
  };
  const std::vector<Body> bodies = {sphere(3, 0, 0, 0, 1), sphere(3, 0.9, 0.2, 0.1, 0.7), sphere(2, 0.3, 0.8, -0.2, 0.5)};
  Params raw;
  raw.sliver_angle_deg = 0;
  const Result cut = compute_union(bodies, raw);
  int under = 0;
  for (const auto& t : cut.faces) {
    const double a = smallest_angle(cut.vertices[t[0]], cut.vertices[t[1]], cut.vertices[t[2]]) / kDeg;
    under += a < kReportedSliverDeg;
  }
  // The icospheres' own faces are far above 5 deg: every sliver of the raw cut is the cut's.
  EXPECT_GT(cut.slivers_left, 10);
  EXPECT_EQ(cut.slivers_left, under);
  const Result improved = compute_union(bodies, Params{});
  EXPECT_EQ(improved.slivers_left, 0);
  EXPECT_GE(improved.min_angle_deg, kReportedSliverDeg);
}
