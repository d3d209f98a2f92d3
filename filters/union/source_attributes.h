// Where each face and vertex of a union lies on the input bodies, so that per-face and
// per-vertex attributes of the bodies (colour, quality, anything a host keeps) can be
// carried over to the result: a face takes its source face's values, a vertex the values
// of its source face's corners weighted by its barycentric coordinates there.
#pragma once

#include "union/surface_union.h"

#include <array>
#include <vector>

namespace mr::surface_union {

/// An input face: body index and face index within that body.
struct FaceOrigin {
  int body = -1, face = -1;
};

/// A point on an input face: weights of the face's corners (in the body's own corner
/// order), non-negative and summing to 1.
struct PointOrigin {
  FaceOrigin face;
  std::array<double, 3> weight{1, 0, 0};
};

/// Per face of `r`: its body (from Result::face_source, without looking for its origin).
std::vector<int> face_bodies(const Result& r, const std::vector<Body>& bodies);

/// Per face of `r`: the input face of its body nearest to its centroid, found by a walk
/// over the body's faces from Result::face_source (the face it was cut from: the sliver
/// step may have moved it a few faces away). `bodies` are the ones compute_union was given.
std::vector<FaceOrigin> face_origins(const Result& r, const std::vector<Body>& bodies);

/// Per vertex of `r`: an input vertex at the same place when one of its faces' sources
/// has a corner there (weight 1 on it; the first such face), else the nearest point on the
/// input, walking from its first face's origin (intersection points; vertices the sliver
/// step moved).
std::vector<PointOrigin> vertex_origins(const Result& r, const std::vector<Body>& bodies);

}  // namespace mr::surface_union
