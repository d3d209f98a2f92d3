#include "remesh/feature_front.h"

#include "common/segment_geometry.h"
#include "remesh/corner_merging.h"
#include "remesh/face_rings.h"
#include "remesh/strip_staggering.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

namespace mr::remesh {

namespace {

double distance_to_polyline(const Point3& p, const std::vector<Point3>& to) {
  double best = to.empty() ? std::numeric_limits<double>::max() : (p - to[0]).Norm();
  for (size_t k = 0; k + 1 < to.size(); ++k) best = std::min(best, point_segment_distance(p, to[k], to[k + 1]));
  return best;
}

// Integral of 1/h along each segment, h linear from sizes[j] to sizes[j + 1]:
// L ln(h1 / h0) / (h1 - h0), or L / h where the two are nearly the same.
double normalised_length(double length, double h0, double h1) {
  h0 = std::max(h0, 1e-300);
  h1 = std::max(h1, 1e-300);
  const double r = h1 / h0;
  if (std::fabs(r - 1) < 1e-6) return length / (0.5 * (h0 + h1));
  return length * std::log(r) / (h1 - h0);
}

std::vector<double> normalised_lengths(const std::vector<double>& lengths, const std::vector<double>& sizes) {
  std::vector<double> out(lengths.size());
  for (size_t j = 0; j < lengths.size(); ++j) out[j] = normalised_length(lengths[j], sizes[j], sizes[j + 1]);
  return out;
}

// Where along a segment (0..1) its normalised length reaches the share `t` (0..1) of its whole,
// h linear from h0 to h1: points spaced evenly in it follow the size, as a long input edge from a
// capped corner to an uncapped one asks (evenly along the edge, the faces at the capped end were
// as long as at the other: rabbit.obj's ear tips at 2%, 26 degrees).
double share_along_segment(double t, double h0, double h1) {
  h0 = std::max(h0, 1e-300);
  h1 = std::max(h1, 1e-300);
  const double r = h1 / h0;
  if (std::fabs(r - 1) < 1e-6) return t;
  return std::clamp((std::pow(r, t) - 1) / (r - 1), 0.0, 1.0);
}

// A patch no element of the local size fits in: two open lines between the same two corners
// (or corners merged into one point, corner_merging.h) closer than kSliverGap x size, with every
// face of the patch between them having all its vertices on the two lines. The twin line gets
// the points of the first and the patch is dropped.

struct Slivers {
  std::vector<int> twin_of;  ///< per line: the line whose points it takes, or -1
  std::vector<char> dropped_patch;
};

Slivers find_slivers(const features::Result& fr, const Surface& s, const FaceRings& vf, const SizeField& size,
                     const CornerMerging& merging) {
  Slivers sl{std::vector<int>(fr.lines.size(), -1), std::vector<char>(fr.patch_count, 0)};
  std::vector<int> patch_faces(fr.patch_count, 0);
  for (int g : s.group) patch_faces[g]++;
  std::map<std::pair<int, int>, std::vector<int>> by_ends;
  for (size_t i = 0; i < fr.lines.size(); ++i) {
    const auto& l = fr.lines[i];
    if (l.closed || l.vertices.size() < 2 || merging.dropped_line[i]) continue;
    const int a = merging.representative[l.vertices.front()], b = merging.representative[l.vertices.back()];
    if (a != b) by_ends[std::minmax(a, b)].push_back(int(i));
  }
  for (const auto& [ends, ids] : by_ends) {
    if (ids.size() != 2) continue;
    const auto &va = fr.lines[ids[0]].vertices, &vb = fr.lines[ids[1]].vertices;
    if (!within_sliver_gap(s, size, va, vb)) continue;
    // The patch between them: its faces around the lines all have their vertices on the lines.
    std::set<int> on_lines(va.begin(), va.end());
    on_lines.insert(vb.begin(), vb.end());
    std::map<int, int> faces_between;
    std::set<int> seen;
    for (int v : on_lines)
      for (int k = vf.begin[v]; k < vf.begin[v + 1]; ++k) {
        const int f = vf.item[k];
        if (!seen.insert(f).second) continue;
        const auto& t = s.faces[f];
        if (on_lines.count(t[0]) && on_lines.count(t[1]) && on_lines.count(t[2])) faces_between[s.group[f]]++;
      }
    for (const auto& [g, n] : faces_between)
      if (n == patch_faces[g] && !sl.dropped_patch[g]) {
        sl.dropped_patch[g] = 1;
        sl.twin_of[ids[1]] = ids[0];
        break;
      }
  }
  return sl;
}

// A thin strip (the rim of a thin plate): every face has its vertices on lines and is lower than
// kSliverGap x size, and the patch's mean width, twice its area over its perimeter, is below
// kSliverGap x size too (the sliver fans of a CAD cap or cylinder side are wide patches).
std::vector<char> find_thin_patches(const features::Result& fr, const Surface& s, const SizeField& size) {
  std::vector<char> on_line(s.points.size(), 0);
  for (const auto& line : fr.lines) for (int v : line.vertices) on_line[v] = 1;
  std::vector<char> thin(fr.patch_count, 1);
  std::vector<double> area(fr.patch_count, 0.0), perimeter(fr.patch_count, 0.0);
  std::vector<double> h_min(fr.patch_count, std::numeric_limits<double>::max());
  for (size_t f = 0; f < s.faces.size(); ++f) {
    const auto& t = s.faces[f];
    const int g = s.group[f];
    const Point3 &a = s.points[t[0]], &b = s.points[t[1]], &c = s.points[t[2]];
    const double longest = std::max({(b - a).Norm(), (c - b).Norm(), (a - c).Norm()});
    const double twice_area = ((b - a) ^ (c - a)).Norm();
    const double h = std::min({size.at_vertex(t[0]), size.at_vertex(t[1]), size.at_vertex(t[2])});
    if (!on_line[t[0]] || !on_line[t[1]] || !on_line[t[2]] || (longest > 0 ? twice_area / longest : 0.0) > kSliverGap * h)
      thin[g] = 0;
    area[g] += 0.5 * twice_area;
    h_min[g] = std::min(h_min[g], h);
    for (int z = 0; z < 3; ++z)
      if (fr.ridge[f][z]) perimeter[g] += (s.points[t[(z + 1) % 3]] - s.points[t[z]]).Norm();
  }
  for (int g = 0; g < fr.patch_count; ++g)
    if (thin[g] && !(perimeter[g] > 0 && 2.0 * area[g] / perimeter[g] <= kSliverGap * h_min[g])) thin[g] = 0;
  return thin;
}

// Patches on either side of a line: those of the faces on its first input edge.
std::vector<int> bordered_patches(const Surface& s, const FaceRings& vf, const std::vector<int>& chain) {
  std::vector<int> groups;
  for (int k = vf.begin[chain[0]]; k < vf.begin[chain[0] + 1]; ++k) {
    const auto& t = s.faces[vf.item[k]];
    if (std::count(t.begin(), t.end(), chain[1]) > 0) groups.push_back(s.group[vf.item[k]]);
  }
  std::sort(groups.begin(), groups.end());
  groups.erase(std::unique(groups.begin(), groups.end()), groups.end());
  return groups;
}

// The line's polyline and its points with their arc lengths along it, for sliding them later.
LinePath line_path(const Surface& s, const FaceRings& vf, const std::vector<int>& chain, const std::vector<int>& pts,
                   std::vector<double> arc, bool may_slide) {
  LinePath path;
  for (int v : chain) path.polyline.push_back(s.points[v]);
  for (size_t j = 0; j + 1 < chain.size(); ++j)
    path.segment_host.push_back(vf.begin[chain[j]] < vf.begin[chain[j] + 1] ? vf.item[vf.begin[chain[j]]] : -1);
  path.points = pts;
  path.arc = std::move(arc);
  path.slidable.assign(pts.size(), may_slide ? 1 : 0);
  path.slidable.front() = path.slidable.back() = 0;
  return path;
}

}  // namespace

double polyline_gap(const std::vector<Point3>& a, const std::vector<Point3>& b) {
  auto one_way = [](const std::vector<Point3>& from, const std::vector<Point3>& to) {
    double worst = 0;
    for (const Point3& p : from) worst = std::max(worst, distance_to_polyline(p, to));
    return worst;
  };
  return std::max(one_way(a, b), one_way(b, a));
}

bool within_sliver_gap(const Surface& s, const SizeField& size, const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<Point3> pa, pb;
  double h = std::numeric_limits<double>::max();
  for (int v : a) { pa.push_back(s.points[v]); h = std::min(h, size.at_vertex(v)); }
  for (int v : b) { pb.push_back(s.points[v]); h = std::min(h, size.at_vertex(v)); }
  return polyline_gap(pa, pb) <= kSliverGap * h;
}

int segment_count(const std::vector<double>& lengths, const std::vector<double>& sizes, int min_segments) {
  double total = 0;
  for (double x : normalised_lengths(lengths, sizes)) total += x;
  return std::max(int(std::lround(total)), min_segments);
}

FeatureFront discretise_features(const TriMesh& mesh, const features::Result& fr, const Surface& s,
                                 const SizeField& size, OutputMesh& out, bool merge_tiny_lines) {
  (void)mesh;
  FeatureFront ff;
  ff.patch_front.resize(fr.patch_count);
  const FaceRings vf(s.points.size(), s.faces);
  const CornerMerging merging = merge_tiny_lines ? merge_close_corners(fr, s, vf, size) : CornerMerging::none(fr, s);
  const auto& rep = merging.representative;
  ff.merged_corners = merging.merged_corners;
  std::map<int, int> corner_point;
  for (int c : fr.corners)
    if (rep[c] == c) {
      const int host = vf.begin[c] < vf.begin[c + 1] ? vf.item[vf.begin[c]] : -1;
      corner_point[c] = out.add_point(s.points[c], host, PointKind::Corner);
    }
  for (int c : fr.corners) {
    corner_point[c] = corner_point[rep[c]];
    ff.corner_point.push_back(corner_point[c]);
  }
  // Open lines that share both end corners with another line need two segments, or their
  // chords would coincide; a line whose two corners were merged needs three to bound a patch.
  std::map<std::pair<int, int>, int> end_pairs;
  for (size_t i = 0; i < fr.lines.size(); ++i)
    if (const auto& line = fr.lines[i]; !line.closed && !merging.dropped_line[i]) {
      auto key = std::minmax(rep[line.vertices.front()], rep[line.vertices.back()]);
      end_pairs[{key.first, key.second}]++;
    }

  const Slivers slivers = find_slivers(fr, s, vf, size, merging);
  ff.dropped_patch = slivers.dropped_patch;
  for (int g = 0; g < fr.patch_count; ++g) ff.dropped_patch[g] = ff.dropped_patch[g] || merging.dropped_patch[g];
  ff.thin_patch = find_thin_patches(fr, s, size);
  std::vector<std::vector<int>> line_points(fr.lines.size());
  // Lines with a twin last, so the twin's points exist when they are reused.
  std::vector<int> order;
  for (int pass = 0; pass < 2; ++pass)
    for (size_t i = 0; i < fr.lines.size(); ++i)
      if ((slivers.twin_of[i] >= 0) == (pass == 1)) order.push_back(int(i));

  std::map<int, std::vector<int>> lines_along_thin;  // thin patch -> its lines discretised so far
  std::vector<char> has_twin(fr.lines.size(), 0);
  for (int t : slivers.twin_of) if (t >= 0) has_twin[t] = 1;
  for (int line_id : order) {
    const auto& line = fr.lines[line_id];
    if (merging.dropped_line[line_id]) continue;  // inside a merged corner's point
    const int twin = slivers.twin_of[line_id];  // never a dropped line (find_slivers skips them)
    std::vector<int> chain = line.vertices;
    if (line.closed) chain.push_back(chain.front());
    if (chain.size() < 2) continue;
    const size_t segs = chain.size() - 1;
    std::vector<double> lengths(segs), sizes(chain.size());
    for (size_t j = 0; j < segs; ++j) lengths[j] = (s.points[chain[j + 1]] - s.points[chain[j]]).Norm();
    for (size_t j = 0; j < chain.size(); ++j) sizes[j] = size.at_vertex(chain[j]);
    int min_segments = 1;
    if (line.closed) min_segments = 3;
    else {
      auto key = std::minmax(rep[chain.front()], rep[chain.back()]);
      if (end_pairs[{key.first, key.second}] > 1 || chain.front() == chain.back()) min_segments = 2;
      if (key.first == key.second && chain.front() != chain.back()) min_segments = 3;
    }
    const std::vector<double> w = normalised_lengths(lengths, sizes);
    std::vector<double> cumulative(segs + 1, 0.0);
    for (size_t j = 0; j < segs; ++j) cumulative[j + 1] = cumulative[j] + w[j];
    const double total = cumulative.back();
    // Where the output points go, as normalised arc lengths: staggered against a line across a
    // thin strip already discretised, else evenly.
    std::vector<double> position;
    const int evenly = twin >= 0 ? int(line_points[twin].size()) - 1 : segment_count(lengths, sizes, min_segments);
    if (twin < 0 && evenly >= kMinStaggeredSegments) {
      std::vector<Point3> polyline, opposite;
      for (int v : chain) polyline.push_back(s.points[v]);
      for (int g : bordered_patches(s, vf, chain)) {
        if (!ff.thin_patch[g]) continue;
        for (int other : lines_along_thin[g])
          for (size_t k = 0; k + 1 < line_points[other].size(); ++k)
            opposite.push_back(out.points[line_points[other][k]] * (1 - kStagger) +
                               out.points[line_points[other][k + 1]] * kStagger);
        lines_along_thin[g].push_back(line_id);
      }
      if (!opposite.empty())
        position = staggered_positions(polyline, cumulative, opposite, kSliverGap * *std::min_element(sizes.begin(), sizes.end()));
      if (int(position.size()) - 1 < min_segments) position.clear();
    }
    const bool staggered = !position.empty();
    const int n = staggered ? int(position.size()) - 1 : evenly;
    if (!staggered)
      for (int i = 0; i <= n; ++i) position.push_back(double(i) / n * total);
    auto middle = [&](int i) { return staggered ? 0.5 * (position[i] + position[i + 1]) : (i + 0.5) / n * total; };
    // Input segment and point at normalised arc length x (staggered positions are projections,
    // linear along their segment).
    auto locate_on_line = [&](double x, size_t& seg, double& u) {
      seg = std::upper_bound(cumulative.begin(), cumulative.end(), x) - cumulative.begin();
      seg = std::clamp<size_t>(seg, 1, segs) - 1;
      u = w[seg] > 0 ? std::clamp((x - cumulative[seg]) / w[seg], 0.0, 1.0) : 0.0;
      if (!staggered) u = share_along_segment(u, sizes[seg], sizes[seg + 1]);
    };
    // Points: the ends are corners (or the start of a closed line), the rest lie on the polyline.
    std::vector<int> pts(n + 1);
    auto end_point = [&](int v) {
      auto it = corner_point.find(v);
      if (it != corner_point.end()) return it->second;
      const int host = vf.begin[v] < vf.begin[v + 1] ? vf.item[vf.begin[v]] : -1;
      return out.add_point(s.points[v], host, PointKind::Line);
    };
    if (twin >= 0) {
      // Same points as the twin, in this line's direction.
      pts = line_points[twin];
      if (rep[fr.lines[twin].vertices.front()] != rep[chain.front()]) std::reverse(pts.begin(), pts.end());
      ff.merged_lines++;
    }
    if (twin < 0) pts[0] = end_point(chain.front());
    std::vector<double> along(segs + 1, 0.0), arc(n + 1, 0.0);  // arc lengths of input and output points
    for (size_t j = 0; j < segs; ++j) along[j + 1] = along[j] + lengths[j];
    arc[n] = along[segs];
    for (int i = 1; i < n && twin < 0; ++i) {
      size_t seg; double u;
      locate_on_line(position[i], seg, u);
      arc[i] = along[seg] + u * lengths[seg];
      const Point3 p = s.points[chain[seg]] * (1 - u) + s.points[chain[seg + 1]] * u;
      const int v0 = chain[seg];
      const int host = vf.begin[v0] < vf.begin[v0 + 1] ? vf.item[vf.begin[v0]] : -1;
      pts[i] = out.add_point(p, host, PointKind::Line);
    }
    if (twin < 0) pts[n] = line.closed ? pts[0] : end_point(chain.back());
    line_points[line_id] = pts;
    if (twin < 0) ff.line_paths.push_back(line_path(s, vf, chain, pts, arc, has_twin[line_id] == 0));

    for (int i = 0; i < n; ++i) {
      if (twin < 0) ff.feature_edges.push_back({pts[i], pts[i + 1]});
      size_t seg; double u;
      locate_on_line(middle(i), seg, u);
      const int va = chain[seg], vb = chain[seg + 1];
      // Each face on this input edge puts the output side into its patch's front, oriented
      // the way that face runs the edge (so the patch lies to the side's left).
      std::set<std::pair<int, int>> added;
      for (int k = vf.begin[va]; k < vf.begin[va + 1]; ++k) {
        const int f = vf.item[k];
        if (ff.dropped_patch[s.group[f]]) continue;
        const auto& t = s.faces[f];
        for (int z = 0; z < 3; ++z) {
          const int x = t[z], y = t[(z + 1) % 3];
          if (x == va && y == vb) {
            if (added.insert({s.group[f], 0}).second) ff.patch_front[s.group[f]].push_back({pts[i], pts[i + 1]});
          } else if (x == vb && y == va) {
            if (added.insert({s.group[f], 1}).second) ff.patch_front[s.group[f]].push_back({pts[i + 1], pts[i]});
          }
        }
      }
    }
  }
  for (int g = 0; g < fr.patch_count; ++g) {
    const auto& f = ff.patch_front[g];
    if (f.size() == 3 && f[0][1] == f[1][0] && f[1][1] == f[2][0] && f[2][1] == f[0][0])
      out.island_triangles[OutputMesh::triangle_key(f[0][0], f[1][0], f[2][0])] = g;
  }
  return ff;
}

}  // namespace mr::remesh
