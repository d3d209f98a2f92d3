// Swaps towards the surface: a face pair whose diagonal cuts across a crease of the input turns
// to the diagonal along it; flat pairs and feature edges stay.
#include "remesh/deviation_swaps.h"
#include "remesh/side_faces.h"
#include "remesh/triangle_geometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace mr;
using namespace mr::remesh;

namespace {

constexpr double kRoof = 0.3;  // ridge height of the input roof

// A roof along x over [0,1] x [-1,1]: its ridge y = 0 at height kRoof; faces 0,1 at y < 0.
struct Roof {
  Surface surface;
  SurfaceLocator locator;
  SizeField size;
  Roof()
      : surface(Surface::from_arrays({Point3(0, -1, 0), Point3(1, -1, 0), Point3(0, 0, kRoof), Point3(1, 0, kRoof),
                                      Point3(0, 1, 0), Point3(1, 1, 0)},
                                     {{0, 1, 3}, {0, 3, 2}, {2, 3, 5}, {2, 5, 4}}, {})),
        locator(surface, 0.25), size(surface, std::vector<double>(6, 1.0)) {}
};

// Two ridge points A, B and two points C, D on the slopes, joined by the diagonal C-D across the
// ridge (faces C,D,A and D,C,B).
OutputMesh across_the_ridge() {
  OutputMesh out;
  const int a = out.add_point(Point3(0.2, 0, kRoof), 1, PointKind::Free);
  const int b = out.add_point(Point3(0.8, 0, kRoof), 1, PointKind::Free);
  const int c = out.add_point(Point3(0.5, -0.8, 0.2 * kRoof), 0, PointKind::Free);
  const int d = out.add_point(Point3(0.5, 0.8, 0.2 * kRoof), 3, PointKind::Free);
  out.faces = {{c, d, a}, {d, c, b}};
  out.face_patch = {0, 0};
  return out;
}

bool has_edge(const OutputMesh& out, int a, int b) {
  for (const auto& f : out.faces)
    for (int z = 0; z < 3; ++z)
      if (std::minmax(f[z], f[(z + 1) % 3]) == std::minmax(a, b)) return true;
  return false;
}

double centroid_distance(const OutputMesh& out, const SurfaceLocator& locator) {
  double worst = 0;
  for (const auto& f : out.faces) {
    const Point3 g = (out.points[f[0]] + out.points[f[1]] + out.points[f[2]]) / 3.0;
    worst = std::max(worst, locator.locate(g, -1, Point3(0, 0, 0), -1, 1.0).distance);
  }
  return worst;
}

}  // namespace

TEST(DeviationSwaps, DiagonalAcrossACreaseTurnsAlongIt) {
  const Roof roof;
  OutputMesh out = across_the_ridge();
  const double before = centroid_distance(out, roof.locator);
  ASSERT_GT(before, 0.1);  // the pair cuts under the ridge

  EXPECT_EQ(swap_towards_surface(out, {}, roof.locator, roof.size), 1);
  EXPECT_TRUE(has_edge(out, 0, 1));
  EXPECT_FALSE(has_edge(out, 2, 3));
  // Each new face lies on one slope of the roof.
  EXPECT_LT(centroid_distance(out, roof.locator), 1e-9);
  // Orientation is kept: both faces face up like the roof.
  for (const auto& f : out.faces) EXPECT_GT(unit_normal(out.points[f[0]], out.points[f[1]], out.points[f[2]])[2], 0.5);
  // And the smallest angle did not get worse than min(30 degrees, the old one).
  for (const auto& f : out.faces) EXPECT_GT(min_angle(out.points[f[0]], out.points[f[1]], out.points[f[2]]) * 180 / M_PI, 30.0);
}

TEST(DeviationSwaps, FeatureEdgesStay) {
  const Roof roof;
  OutputMesh out = across_the_ridge();
  EXPECT_EQ(swap_towards_surface(out, {{{3, 2}}}, roof.locator, roof.size), 0);
  EXPECT_TRUE(has_edge(out, 2, 3));
}

TEST(DeviationSwaps, PairsNearTheSurfaceStay) {
  const Roof roof;
  OutputMesh out = across_the_ridge();
  // Raise the slope points next to the ridge: the diagonal is then within 0.1 x size of the roof.
  out.points[2] = Point3(0.5, -0.1, 0.9 * kRoof);
  out.points[3] = Point3(0.5, 0.1, 0.9 * kRoof);
  EXPECT_EQ(swap_towards_surface(out, {}, roof.locator, roof.size), 0);
}

TEST(SideFaces, SwapsAndUndoKeepEverySideWithItsFace) {
  // A fan of 6 faces around point 0 (a hexagon): swap each spoke that can be, undo half of them,
  // and after every step each directed side must map to the face that has it.
  OutputMesh out;
  out.add_point(Point3(0, 0, 0), 0, PointKind::Free);
  for (int k = 0; k < 6; ++k) out.add_point(Point3(std::cos(k * M_PI / 3), std::sin(k * M_PI / 3), 0), 0, PointKind::Free);
  for (int k = 0; k < 6; ++k) out.faces.push_back({0, 1 + k, 1 + (k + 1) % 6});
  out.face_patch.assign(6, 0);
  SideFaces sides(out.faces);
  auto consistent = [&] {
    for (size_t f = 0; f < out.faces.size(); ++f)
      for (int z = 0; z < 3; ++z)
        if (sides.face_of(out.faces[f][z], out.faces[f][(z + 1) % 3]) != int(f)) return false;
    return true;
  };
  int swapped = 0;
  for (int f = 0; f < 6; ++f)
    for (int z = 0; z < 3; ++z) {
      FacePair p;
      if (!sides.swappable_pair(out, f, z, p)) continue;
      const auto before_f = out.faces[p.f], before_g = out.faces[p.g];
      sides.swap(out, p);
      ++swapped;
      ASSERT_TRUE(consistent());
      EXPECT_TRUE(sides.has_edge(p.c, p.d));
      EXPECT_FALSE(sides.has_edge(p.x, p.y));
      if (swapped % 2 == 0) {  // undo
        sides.set_face(out, p.f, before_f);
        sides.set_face(out, p.g, before_g);
        ASSERT_TRUE(consistent());
        EXPECT_TRUE(sides.has_edge(p.x, p.y));
      }
    }
  EXPECT_GT(swapped, 1);
}
