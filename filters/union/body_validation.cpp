#include "union/body_validation.h"

#include "common/edge_table.h"
#include "common/errors.h"
#include "common/parallel_for.h"
#include "union/exact.h"
#include "union/self_intersection.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace mr::surface_union {

namespace {

std::string label(const Body& b, size_t index) {
  return b.name.empty() ? "body " + std::to_string(index) : "body " + std::to_string(index) + " ('" + b.name + "')";
}

bool degenerate(const Body& b, const std::array<int, 3>& f) {
  const double *p = b.vertices[f[0]].data(), *q = b.vertices[f[1]].data(), *r = b.vertices[f[2]].data();
  return orient2d(p, q, r, 0, 1) == 0 && orient2d(p, q, r, 1, 2) == 0 && orient2d(p, q, r, 2, 0) == 0;
}

TopologyError crosses_itself(const Body& b, size_t i, const std::array<int, 2>& pair) {
  return TopologyError(label(b, i) + " intersects itself (its faces " + std::to_string(pair[0]) + " and " +
                       std::to_string(pair[1]) + " cross): the union needs bodies with an inside; repair it "
                       "first (Filters > Selection > Select Self Intersecting Faces shows where)");
}

/// Checks body i and turns it outward if it is inward; returns whether it did.
bool validate_body(Body& b, size_t i) {
  const std::string name = label(b, i);
  if (b.vertices.empty() || b.faces.empty()) throw InvalidInput(name + " is empty: it has no faces");
  // The floating-point filters multiply up to six coordinates (differences) and would
  // overflow or underflow beyond this range (measured: 1e75 fails, 1e-100 leaves the
  // slivers untreated); the exact fallback cannot help where the filter gives NaN.
  constexpr double kLargest = 1e50, kSmallestExtent = 1e-50;
  std::array<double, 3> lo = b.vertices[0], hi = b.vertices[0];
  for (const auto& v : b.vertices)
    for (size_t k = 0; k < 3; ++k) {
      if (!std::isfinite(v[k]))
        throw InvalidInput(name + " has NaN or infinite vertex coordinates: fix or delete those vertices");
      if (std::fabs(v[k]) > kLargest)
        throw InvalidInput(name + " has vertex coordinates beyond 1e50 in magnitude: scale the model down first "
                                  "(Normals, Curvatures and Orientation > Transform: Scale, Normalize)");
      lo[k] = std::min(lo[k], v[k]);
      hi[k] = std::max(hi[k], v[k]);
    }
  if (std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}) < kSmallestExtent)
    throw InvalidInput(name + " is smaller than 1e-50 across: scale the model up first "
                              "(Normals, Curvatures and Orientation > Transform: Scale, Normalize)");
  const int nv = int(b.vertices.size());
  for (const auto& f : b.faces) {
    for (int z = 0; z < 3; ++z)
      if (f[z] < 0 || f[z] >= nv) throw InvalidInput(name + " has a face with an invalid vertex index");
    if (degenerate(b, f))
      throw InvalidInput(name + " has degenerate (zero-area) faces: remove them first "
                                "(Cleaning and Repairing > Remove Zero Area Faces)");
  }
  // Closed, manifold and consistently oriented: each edge has two face sides, one running
  // from its lower vertex and one towards it.
  const EdgeTable edges(b.vertices.size(), b.faces);
  int open = 0, nonmanifold = 0, misoriented = 0;
  for (int e = 0; e < edges.edge_count(); ++e) {
    const int n = edges.valence(e);
    if (n == 1) ++open;
    else if (n > 2) ++nonmanifold;
    else {
      int forward = 0;
      for (int k = 0; k < 2; ++k) {
        const FaceSide fs = edges.side(e, k);
        forward += b.faces[size_t(fs.face)][size_t(fs.side)] == edges.v0(e);
      }
      misoriented += forward != 1;
    }
  }
  if (open) throw TopologyError(name + " is not closed (" + std::to_string(open) +
                                " boundary edges): close its holes first (Remeshing > Close Holes), or weld "
                                "duplicate vertices if it is a triangle soup such as an STL file");
  if (nonmanifold)
    throw TopologyError(name + " is non-manifold (" + std::to_string(nonmanifold) +
                        " edges with more than two faces): repair it first (Cleaning and Repairing > "
                        "Repair non Manifold Edges)");
  if (misoriented)
    throw TopologyError(name + " is not consistently oriented (" + std::to_string(misoriented) +
                        " edges): reorient it first (Cleaning and Repairing > Re-Orient all faces coherently)");
  // Signed volume decides inward/outward.
  if (!faces_outward(b)) {
    for (auto& f : b.faces) std::swap(f[1], f[2]);
    return true;
  }
  return false;
}

}  // namespace

int validate_bodies(std::vector<Body>& bodies) {
  if (bodies.empty()) throw InvalidInput("there are no bodies: give visible layers or a mesh with closed components");
  // Bodies are independent: checked in parallel, and the first bad one in order is the
  // one reported, whatever thread found it.
  std::vector<std::exception_ptr> error(bodies.size());
  std::vector<char> flipped(bodies.size(), 0);
  parallel_for(bodies.size(), 1, [&](size_t i) {
    try {
      flipped[i] = validate_body(bodies[i], i);
    } catch (...) {
      error[i] = std::current_exception();
    }
  });
  for (const auto& e : error)
    if (e) std::rethrow_exception(e);
  return int(std::count(flipped.begin(), flipped.end(), 1));
}

SelfIntersectionCheck::SelfIntersectionCheck(const std::vector<Body>& bodies)
    : bodies_(bodies), first_part_(bodies.size() + 1, 0), scan_(bodies.size()),
      built_(new std::once_flag[bodies.size()]) {
  for (size_t i = 0; i < bodies.size(); ++i)
    first_part_[i + 1] = first_part_[i] + std::max<size_t>(1, (bodies[i].faces.size() + kPartFaces - 1) / kPartFaces);
  crossing_.resize(first_part_.back());
  error_.resize(first_part_.back());
  if (worker_count() <= 1) finish();
}

SelfIntersectionCheck::~SelfIntersectionCheck() {
  if (thread_.joinable()) thread_.join();
}

void SelfIntersectionCheck::start(std::function<void()> first, std::function<void()> then) {
  if (worker_count() > 1 && !thread_.joinable()) {
    try {
      thread_ = std::thread([this, first = std::move(first), then = std::move(then)] {
        first();
        if (then) then();
        work();
      });
      return;
    } catch (const std::system_error&) {
      // no thread to be had: finish() checks them all
    }
  }
  first();
}

bool SelfIntersectionCheck::check_next() {
  const size_t part = next_.fetch_add(1);
  if (part >= first_part_.back()) return false;
  const size_t i = size_t(std::upper_bound(first_part_.begin(), first_part_.end(), part) - first_part_.begin()) - 1;
  // Each thread keeps its own marks for the grids' lookups (their stamps only grow).
  thread_local FaceGrid::Marks marks;
  try {
    // (The bodies face outward now: validate_bodies turned the others.) A thread taking
    // a later part of the body waits here for the one building it.
    std::call_once(built_[i], [&] { scan_[i] = std::make_unique<SelfIntersectionScan>(bodies_[i]); });
    if (!scan_[i]) throw std::runtime_error("self-intersection check of " + label(bodies_[i], i) + " was not built");
    const int begin = int((part - first_part_[i]) * kPartFaces);
    const int end = std::min(int(bodies_[i].faces.size()), begin + kPartFaces);
    crossing_[part] = scan_[i]->scan(begin, end, marks);
  } catch (...) {
    error_[part] = std::current_exception();
  }
  return true;
}

void SelfIntersectionCheck::work() {
  while (check_next()) {
  }
}

void SelfIntersectionCheck::finish() {
  work();
  if (thread_.joinable()) thread_.join();
  scan_.clear();  // the grids
  for (size_t i = 0; i < bodies_.size(); ++i)
    for (size_t part = first_part_[i]; part < first_part_[i + 1]; ++part) {
      if (error_[part]) std::rethrow_exception(error_[part]);
      if (crossing_[part]) throw crosses_itself(bodies_[i], i, *crossing_[part]);
    }
}

}  // namespace mr::surface_union
