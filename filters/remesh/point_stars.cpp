#include "remesh/point_stars.h"

#include <algorithm>
#include <iterator>

namespace mr::remesh {

PointStars::PointStars(const OutputMesh& out) : star_(out.points.size()) {
  for (size_t f = 0; f < out.faces.size(); ++f)
    for (int v : out.faces[f]) star_[size_t(v)].push_back(int(f));
}

std::vector<int> PointStars::neighbours(const OutputMesh& out, int v) const {
  std::vector<int> n;
  for (int k : of(v))
    for (int x : out.faces[size_t(k)])
      if (x != v) n.push_back(x);
  std::sort(n.begin(), n.end());
  n.erase(std::unique(n.begin(), n.end()), n.end());
  return n;
}

std::vector<int> PointStars::faces_on(const OutputMesh& out, int v, int w) const {
  std::vector<int> on;
  for (int k : of(v)) {
    const auto& t = out.faces[size_t(k)];
    if (t[0] == w || t[1] == w || t[2] == w) on.push_back(k);
  }
  return on;
}

bool PointStars::link_condition(const OutputMesh& out, int v, int w, const std::vector<int>& dying) const {
  std::vector<int> opposite;
  for (int k : dying)
    for (int x : out.faces[size_t(k)])
      if (x != v && x != w) opposite.push_back(x);
  std::sort(opposite.begin(), opposite.end());
  const std::vector<int> nv = neighbours(out, v), nw = neighbours(out, w);
  std::vector<int> common;
  std::set_intersection(nv.begin(), nv.end(), nw.begin(), nw.end(), std::back_inserter(common));
  return common == opposite;
}

void PointStars::collapse(OutputMesh& out, int v, int w, const std::vector<int>& dying) {
  for (int k : dying) {
    for (int x : out.faces[size_t(k)]) {
      auto& s = of(x);
      s.erase(std::remove(s.begin(), s.end(), k), s.end());
    }
    out.faces[size_t(k)] = {-1, -1, -1};
  }
  for (int k : of(v)) {
    for (int& x : out.faces[size_t(k)])
      if (x == v) x = w;
    of(w).push_back(k);
  }
  of(v).clear();
}

void drop_dead_faces(OutputMesh& out) {
  size_t n = 0;
  for (size_t f = 0; f < out.faces.size(); ++f) {
    if (out.faces[f][0] < 0) continue;
    out.faces[n] = out.faces[f];
    out.face_patch[n++] = out.face_patch[f];
  }
  out.faces.resize(n);
  out.face_patch.resize(n);
}

}  // namespace mr::remesh
