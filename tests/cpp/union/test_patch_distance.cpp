// patches_within: the sliver step's comparison of the faces a move replaces with the
// faces it makes.
#include "union/patch_distance.h"

#include <gtest/gtest.h>

#include <vector>

using namespace mr::surface_union;

namespace {

// A square [0,1]^2 at height z, as two triangles split along one diagonal or the other.
std::vector<Triangle> square(double z, bool other_diagonal) {
  const V3 a{0, 0, z}, b{1, 0, z}, c{1, 1, z}, d{0, 1, z};
  if (other_diagonal) return {{a, b, d}, {b, c, d}};
  return {{a, b, c}, {a, c, d}};
}

}  // namespace

TEST(UnionPatchDistance, SameSquareOtherDiagonalIsWithinAnyLimit) {
  EXPECT_TRUE(patches_within(square(0, false), square(0, true), 1e-12));
}

TEST(UnionPatchDistance, ATentIsWithinItsHeightOnly) {
  // The centre raised by h: the old flat fan and the tent differ by h at the centre, by
  // h/2 at the midpoints of the spokes.
  const double h = 0.1;
  const V3 a{0, 0, 0}, b{1, 0, 0}, c{1, 1, 0}, d{0, 1, 0}, m{0.5, 0.5, 0}, t{0.5, 0.5, h};
  const std::vector<Triangle> flat{{a, b, m}, {b, c, m}, {c, d, m}, {d, a, m}};
  const std::vector<Triangle> tent{{a, b, t}, {b, c, t}, {c, d, t}, {d, a, t}};
  EXPECT_TRUE(patches_within(flat, tent, h));
  EXPECT_FALSE(patches_within(flat, tent, h / 4));
}

TEST(UnionPatchDistance, AFoldedFanIsFarFromTheTriangleThatReplacesIt) {
  // A fin: the ring a, b, c with the removed vertex v close to corner b, folded back over
  // the ring, so that v is near the plane of (a, b, c) but the fan covers almost nothing
  // of that triangle. A bound on v's distance from the new face would pass it.
  const V3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, v{0.98, 0.01, 0.001};
  const std::vector<Triangle> fan{{a, b, v}, {b, c, v}, {c, a, v}};
  const std::vector<Triangle> filled{{a, b, c}};
  EXPECT_TRUE(patches_within(fan, filled, 0.002));  // the fan lies on the triangle
  const V3 far{0.98, 0.01, 0.5};                    // folded up: the fan leaves the plane
  const std::vector<Triangle> fin{{a, b, far}, {b, c, far}, {c, a, far}};
  EXPECT_FALSE(patches_within(fin, filled, 0.01));
  EXPECT_FALSE(patches_within(filled, fin, 0.01));
}

TEST(UnionPatchDistance, AnAxisPlaneIsKnownFlatWithoutSampling) {
  // Both patches in the plane z = 2: the same polygon, whatever the limit.
  EXPECT_TRUE(patches_within(square(2, false), square(2, true), 0));
  EXPECT_FALSE(patches_within(square(2, false), square(2.5, true), 0.4));
}
