// Faces that rounding flattened onto one of their sides: removed by splitting the
// neighbour at the apex, or, with a cap on both sides, by zipping the two chains.
#include "union/rounded_caps.h"
#include "union/rounded_edges.h"
#include "union/surface_union.h"
#include "union_checks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace mr;
using namespace mr::surface_union;

namespace {

using V = std::array<double, 3>;

/// Largest angle of the worst face, degrees: a cap has one of ~180.
double largest_angle(const Result& r) {
  double worst = 0;
  for (const auto& t : r.faces)
    for (int z = 0; z < 3; ++z) {
      const V &a = r.vertices[size_t(t[size_t(z)])], &b = r.vertices[size_t(t[size_t((z + 1) % 3)])],
              &c = r.vertices[size_t(t[size_t((z + 2) % 3)])];
      const V u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const V n{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      const double angle = std::atan2(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), u[0] * w[0] + u[1] * w[1] + u[2] * w[2]);
      worst = std::max(worst, angle * 180 / 3.14159265358979323846);
    }
  return worst;
}

/// Both faces of every edge agree on its line flag; returns the number of line edges.
int consistent_line_edges(const Result& r) {
  std::map<std::pair<int, int>, std::vector<bool>> flags;
  for (size_t f = 0; f < r.faces.size(); ++f)
    for (int z = 0; z < 3; ++z) {
      const int a = r.faces[f][size_t(z)], b = r.faces[f][size_t((z + 1) % 3)];
      flags[{std::min(a, b), std::max(a, b)}].push_back(r.line_edge[f][size_t(z)]);
    }
  int lines = 0;
  for (const auto& [edge, fl] : flags) {
    EXPECT_EQ(fl.size(), 2u);
    EXPECT_EQ(fl.front(), fl.back()) << edge.first << "-" << edge.second;
    lines += fl.front();
  }
  return lines;
}

/// An octahedron (0..5: +x, +y, -x, -y, -z, +z) whose edge 0 -> 1 carries a cap (0, 1, 6) on
/// top, the top face split at 6 (the cap's apex, at `t` along the edge and `off` beside it);
/// with `t2` > 0 also a cap (1, 0, 7) below, the bottom face split at 7. The edge is a line.
Result octahedron_with_caps(double t, double off, double t2 = 0, double off2 = 0) {
  Result r;
  r.vertices = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}, {0, 0, 1}};
  auto on_edge = [&](double s, double o) { return V{1 - s + o, s + o, 0}; };
  r.vertices.push_back(on_edge(t, off));  // 6
  r.faces = {{0, 6, 5}, {6, 1, 5}, {0, 1, 6}, {5, 1, 2}, {5, 2, 3}, {5, 3, 0}, {4, 2, 1}, {4, 3, 2}, {4, 0, 3}};
  if (t2 > 0) {
    r.vertices.push_back(on_edge(t2, off2));  // 7
    r.faces.push_back({1, 7, 4});
    r.faces.push_back({7, 0, 4});
    r.faces.push_back({1, 0, 7});
  } else {
    r.faces.push_back({1, 0, 4});
  }
  r.line_edge.assign(r.faces.size(), {false, false, false});
  r.line_edge[2][0] = true;              // (0 -> 1) of the cap
  r.line_edge[r.faces.size() - 1][0] = true;  // (1 -> 0) below
  r.face_source.resize(r.faces.size());
  for (size_t f = 0; f < r.faces.size(); ++f) r.face_source[f] = int(f);
  return r;
}

}  // namespace

TEST(RoundedCaps, ACapAloneGoesByTheNeighboursSplit) {
  for (double off : {0.0, 1e-16, -1e-16}) {  // on the side, and rounded to either side of it
    Result r = octahedron_with_caps(0.5, off);
    std::vector<char> cut(r.faces.size(), 1);
    ASSERT_GT(largest_angle(r), 179.9);
    const size_t faces = r.faces.size();
    EXPECT_EQ(split_rounded_caps(r, cut), 1);
    EXPECT_EQ(r.faces.size(), faces);
    EXPECT_LT(largest_angle(r), 135.0);
    EXPECT_TRUE(test::watertight(r).ok());
    EXPECT_EQ(consistent_line_edges(r), 2);  // the line runs 0 -> 6 -> 1 now
  }
}

TEST(RoundedCaps, CapsOnBothSidesAreZipped) {
  for (const auto& [t, t2] : {std::pair{0.3, 0.6}, std::pair{0.6, 0.3}}) {
    Result r = octahedron_with_caps(t, 1e-16, t2, -1e-16);
    std::vector<char> cut(r.faces.size(), 1);
    const size_t faces = r.faces.size();
    EXPECT_EQ(split_rounded_caps(r, cut), 1);
    EXPECT_EQ(r.faces.size(), faces);
    EXPECT_LT(largest_angle(r), 150.0);
    EXPECT_TRUE(test::watertight(r).ok());
    EXPECT_EQ(consistent_line_edges(r), 3);  // 0 -> 6 -> 7 -> 1 or 0 -> 7 -> 6 -> 1
    EXPECT_GT(test::volume(r), 0);
  }
}

TEST(RoundedCaps, CapsWithApexesAtOnePlaceAreFlippedAndMerged) {
  Result r = octahedron_with_caps(0.5, 0, 0.5, 0);
  std::vector<char> cut(r.faces.size(), 1);
  int flipped = 0;
  EXPECT_EQ(split_rounded_caps(r, cut, &flipped), 1);
  EXPECT_EQ(flipped, 1);
  EXPECT_EQ(merge_rounded_together(r, cut), 1);
  EXPECT_EQ(r.faces.size(), 10u);  // the two caps gone, the apexes one vertex
  EXPECT_LT(largest_angle(r), 135.0);
  EXPECT_TRUE(test::watertight(r).ok());
  EXPECT_EQ(consistent_line_edges(r), 2);
}

TEST(RoundedCaps, FacesThatAreOnlyThinStay) {
  // An apex 1e-6 beside the side is a sliver for the sliver step, not a rounding cap.
  Result r = octahedron_with_caps(0.5, 1e-6);
  std::vector<char> cut(r.faces.size(), 1);
  EXPECT_EQ(split_rounded_caps(r, cut), 0);
}
