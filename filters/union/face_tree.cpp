#include "union/face_tree.h"

#include <algorithm>
#include <numeric>

namespace mr::surface_union {
namespace {

constexpr int kLeafSize = 4;

double box_distance2(const V3& p, const V3& lo, const V3& hi) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = p[k] < lo[k] ? lo[k] - p[k] : (p[k] > hi[k] ? p[k] - hi[k] : 0);
    d2 += d * d;
  }
  return d2;
}

}  // namespace

FaceTree::FaceTree(const std::vector<V3>& vertices, const std::vector<std::array<int, 3>>& faces,
                   const std::vector<int>& which) {
  std::vector<std::array<V3, 3>> corners;
  std::vector<V3> centroids;
  corners.reserve(which.size());
  centroids.reserve(which.size());
  for (int f : which) {
    const auto& t = faces[size_t(f)];
    corners.push_back({vertices[t[0]], vertices[t[1]], vertices[t[2]]});
    const auto& q = corners.back();
    centroids.push_back({(q[0][0] + q[1][0] + q[2][0]) / 3, (q[0][1] + q[1][1] + q[2][1]) / 3,
                         (q[0][2] + q[1][2] + q[2][2]) / 3});
  }
  if (corners.empty()) return;
  std::vector<int> order(corners.size());
  std::iota(order.begin(), order.end(), 0);
  nodes_.reserve(2 * corners.size() / kLeafSize + 2);
  build(0, int(order.size()), order, corners, centroids);
  triangles_.reserve(order.size());
  for (int i : order) {
    const auto& t = corners[size_t(i)];
    triangles_.emplace_back(t[0], t[1], t[2]);
  }
}

int FaceTree::build(int first, int count, std::vector<int>& order, const std::vector<std::array<V3, 3>>& corners,
                    const std::vector<V3>& centroids) {
  const int id = int(nodes_.size());
  nodes_.push_back({});
  Node node;
  V3 clo = centroids[size_t(order[first])], chi = clo;
  for (int i = first; i < first + count; ++i) {
    const V3& c = centroids[size_t(order[i])];
    for (int k = 0; k < 3; ++k) {
      clo[k] = std::min(clo[k], c[k]);
      chi[k] = std::max(chi[k], c[k]);
    }
  }
  if (count <= kLeafSize) {  // a leaf's box from its corners, an inner node's from its children's
    node.lo = node.hi = corners[size_t(order[first])][0];
    for (int i = first; i < first + count; ++i)
      for (const V3& p : corners[size_t(order[i])])
        for (int k = 0; k < 3; ++k) {
          node.lo[k] = std::min(node.lo[k], p[k]);
          node.hi[k] = std::max(node.hi[k], p[k]);
        }
    node.first = first;
    node.count = count;
    nodes_[size_t(id)] = node;
    return id;
  }
  // Median split of the centroids along their longest extent (ties by index: the same
  // tree on every run).
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (chi[k] - clo[k] > chi[axis] - clo[axis]) axis = k;
  const int half = count / 2;
  std::nth_element(order.begin() + first, order.begin() + first + half, order.begin() + first + count,
                   [&](int a, int b) {
                     const double ca = centroids[size_t(a)][axis], cb = centroids[size_t(b)][axis];
                     return ca < cb || (ca == cb && a < b);
                   });
  node.left = build(first, half, order, corners, centroids);
  node.right = build(first + half, count - half, order, corners, centroids);
  const Node &l = nodes_[size_t(node.left)], &r = nodes_[size_t(node.right)];
  for (int k = 0; k < 3; ++k) {
    node.lo[k] = std::min(l.lo[k], r.lo[k]);
    node.hi[k] = std::max(l.hi[k], r.hi[k]);
  }
  nodes_[size_t(id)] = node;
  return id;
}

double FaceTree::distance(const V3& p, double enough, double limit, Recent* recent) const {
  if (nodes_.empty()) return 2 * limit + 1;
  const double enough2 = enough * enough;
  double best2 = limit * limit;
  bool found = false;
  auto distance2 = [&](int i) { return triangles_[size_t(i)].squared_distance(p); };
  if (recent)
    for (int f : recent->faces) {
      if (f < 0) continue;
      const double d2 = distance2(f);
      if (d2 <= enough2) return std::sqrt(d2);
      if (d2 <= best2) {
        best2 = d2;
        found = true;
      }
    }
  // A face that ends the search is kept among the recent ones.
  auto keep = [&](int i) {
    if (!recent) return;
    for (int f : recent->faces)
      if (f == i) return;
    recent->faces[recent->next++ % recent->faces.size()] = i;
  };
  // Depth first, each node with its box's distance (computed once, by its parent); the
  // median split keeps the depth at log2 of the faces.
  struct Entry {
    int node;
    double d2;
  };
  Entry stack[128];
  int top = 0;
  stack[top++] = {0, box_distance2(p, nodes_[0].lo, nodes_[0].hi)};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.d2 > best2) continue;
    const Node& node = nodes_[size_t(e.node)];
    if (node.left < 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const double d2 = distance2(i);
        if (d2 <= best2) {
          best2 = d2;
          found = true;
          if (best2 <= enough2) {
            keep(i);
            return std::sqrt(best2);
          }
        }
      }
      continue;
    }
    // The nearer child last on the stack, so it is searched first.
    const Entry l{node.left, box_distance2(p, nodes_[size_t(node.left)].lo, nodes_[size_t(node.left)].hi)};
    const Entry r{node.right, box_distance2(p, nodes_[size_t(node.right)].lo, nodes_[size_t(node.right)].hi)};
    const bool left_first = l.d2 < r.d2;
    const Entry& near = left_first ? l : r;
    const Entry& far = left_first ? r : l;
    if (far.d2 <= best2) stack[top++] = far;
    if (near.d2 <= best2) stack[top++] = near;
  }
  return found ? std::sqrt(best2) : 2 * limit + 1;
}

}  // namespace mr::surface_union
