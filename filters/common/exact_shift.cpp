#include "common/exact_shift.h"

namespace mr {

Point3 exact_shift_towards_origin(const Box3& box) {
  Point3 shift(0, 0, 0);
  if (box.IsNull()) return shift;
  for (int k = 0; k < 3; ++k) {
    const double lo = box.min[k], hi = box.max[k], extent = hi - lo;
    if (lo > extent) shift[k] = lo;
    else if (hi < -extent) shift[k] = hi;
  }
  return shift;
}

void shift_vertices(TriMesh& m, const Point3& shift) {
  for (auto& v : m.vert)
    if (!v.IsD()) v.P() -= shift;
}

}  // namespace mr
