#include "union/body_validation.h"

#include "common/errors.h"
#include "common/parallel_for.h"
#include "union/exact.h"
#include "union/self_intersection.h"

#include <algorithm>
#include <cmath>
#include <exception>
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

/// Checks body i and turns it outward if it is inward; returns whether it did.
bool validate_body(Body& b, size_t i, bool self_intersections) {
  const std::string name = label(b, i);
  if (b.vertices.empty() || b.faces.empty()) throw InvalidInput(name + " is empty: it has no faces");
  for (const auto& v : b.vertices)
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
      throw InvalidInput(name + " has NaN or infinite vertex coordinates: fix or delete those vertices");
  const int nv = int(b.vertices.size());
  for (const auto& f : b.faces) {
    for (int z = 0; z < 3; ++z)
      if (f[z] < 0 || f[z] >= nv) throw InvalidInput(name + " has a face with an invalid vertex index");
    if (degenerate(b, f))
      throw InvalidInput(name + " has degenerate (zero-area) faces: remove them first "
                                "(Cleaning and Repairing > Remove Zero Area Faces)");
  }
  // Directed edge counts: closed, manifold and consistently oriented means each
  // undirected edge is used exactly once in each direction.
  // Half-edges as (min, max, forward) sorted, so each undirected edge is one run: bucketed
  // by the lower vertex (a counting sort), each bucket (a vertex's few edges) then sorted
  // by insertion. std::sort on the triples was a fifth of a two-sphere union.
  std::vector<int> begin(size_t(nv) + 1, 0);
  for (const auto& f : b.faces)
    for (int z = 0; z < 3; ++z) ++begin[size_t(std::min(f[z], f[(z + 1) % 3])) + 1];
  for (int v = 0; v < nv; ++v) begin[size_t(v) + 1] += begin[size_t(v)];
  std::vector<std::array<int, 3>> half(3 * b.faces.size());
  {
    std::vector<int> next(begin.begin(), begin.end() - 1);
    for (const auto& f : b.faces)
      for (int z = 0; z < 3; ++z) {
        const int u = f[z], v = f[(z + 1) % 3];
        half[size_t(next[size_t(std::min(u, v))]++)] = {std::min(u, v), std::max(u, v), u < v ? 1 : 0};
      }
  }
  for (int v = 0; v < nv; ++v) {
    const auto first = half.begin() + begin[size_t(v)], last = half.begin() + begin[size_t(v) + 1];
    if (last - first > 32) std::sort(first, last);  // a fan's apex: no quadratic insertion
    else
      for (auto i = first + (first != last); i < last; ++i)
        for (auto j = i; j > first && *(j - 1) > *j; --j) std::iter_swap(j - 1, j);
  }
  int open = 0, nonmanifold = 0, misoriented = 0;
  for (size_t run = 0; run < half.size();) {
    size_t end = run;
    int forward = 0;
    while (end < half.size() && half[end][0] == half[run][0] && half[end][1] == half[run][1]) forward += half[end++][2];
    const size_t n = end - run;
    if (n == 1) ++open;
    else if (n > 2) ++nonmanifold;
    else if (forward != 1) ++misoriented;
    run = end;
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
  if (const auto pair = self_intersections ? self_intersection(b) : std::nullopt)
    throw TopologyError(name + " intersects itself (its faces " + std::to_string((*pair)[0]) + " and " +
                        std::to_string((*pair)[1]) + " cross): the union needs bodies with an inside; repair it "
                        "first (Filters > Selection > Select Self Intersecting Faces shows where)");
  // Signed volume decides inward/outward.
  double vol = 0;
  for (const auto& f : b.faces) {
    const auto &p = b.vertices[f[0]], &q = b.vertices[f[1]], &r = b.vertices[f[2]];
    vol += p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) + p[2] * (q[0] * r[1] - q[1] * r[0]);
  }
  if (vol < 0) {
    for (auto& f : b.faces) std::swap(f[1], f[2]);
    return true;
  }
  return false;
}

}  // namespace

int validate_bodies(std::vector<Body>& bodies, bool self_intersections) {
  if (bodies.empty()) throw InvalidInput("there are no bodies: give visible layers or a mesh with closed components");
  // Bodies are independent: checked in parallel, and the first bad one in order is the
  // one reported, whatever thread found it.
  std::vector<std::exception_ptr> error(bodies.size());
  std::vector<char> flipped(bodies.size(), 0);
  parallel_for(bodies.size(), 1, [&](size_t i) {
    try {
      flipped[i] = validate_body(bodies[i], i, self_intersections);
    } catch (...) {
      error[i] = std::current_exception();
    }
  });
  for (const auto& e : error)
    if (e) std::rethrow_exception(e);
  return int(std::count(flipped.begin(), flipped.end(), 1));
}

}  // namespace mr::surface_union
