#include "union/surface_union.h"

#include "common/background_release.h"
#include "common/errors.h"
#include "common/parallel_for.h"
#include "common/side_worker.h"
#include "common/union_find.h"
#include "union/body_validation.h"
#include "union/candidate_pairs.h"
#include "union/doubled_edges.h"
#include "union/face_triangulation.h"
#include "union/outside_surface.h"
#include "union/rounded_caps.h"
#include "union/rounded_edges.h"
#include "union/sliver_collapse.h"
#include "union/slivers_left.h"
#include "union/triangle_intersection.h"

#include <vcg/complex/algorithms/clean.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <set>

namespace mr::surface_union {

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

/// Sub-face `sub` of a face cut along coplanar soup face g lies inside g, exactly. The
/// cut follows g's sides, so the sub-face lies inside or outside g as a whole: inside
/// exactly when no corner is strictly outside (no rational centroid needed; corners
/// built on a side of g are known to lie on it).
bool inside_coplanar(const PointTable& pts, const std::vector<int>& vertex_point, const Soup& soup, int g,
                     const std::array<int, 3>& sub, const Projection& pr) {
  const auto& G = soup.face[g];
  const int q[3] = {vertex_point[G[0]], vertex_point[G[1]], vertex_point[G[2]]};
  const int so = orient2d(pts[q[0]], pts[q[1]], pts[q[2]], pr.i, pr.j);
  for (int e = 0; e < 3; ++e) {
    const int u = q[e], w = q[(e + 1) % 3];
    for (int x : sub) {
      if (x == u || x == w) continue;
      int side = orient2d_filter(pts[u], pts[w], pts[x], pr.i, pr.j);
      if (side == 2) side = pts.known_collinear(u, w, x) ? 0 : orient2d(pts[u], pts[w], pts[x], pr.i, pr.j);
      if (so * side < 0) return false;
    }
  }
  return true;
}

void chain_lines(Result& r) {
  // Undirected line edges, each once, and each vertex's line edges in flat arrays
  // (sets and a hash map of vectors took ~0.14 s on the 2000-sphere cluster).
  std::vector<std::pair<int, int>> edges;
  for (size_t f = 0; f < r.faces.size(); ++f)
    for (int z = 0; z < 3; ++z)
      if (r.line_edge[f][z]) {
        const int u = r.faces[f][z], w = r.faces[f][(z + 1) % 3];
        edges.push_back({std::min(u, w), std::max(u, w)});
      }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const size_t nv = r.vertices.size();
  std::vector<int> first(nv + 1, 0);  // vertex x's edges: at_vertex[first[x] .. first[x + 1])
  for (const auto& [u, w] : edges) { ++first[size_t(u) + 1]; ++first[size_t(w) + 1]; }
  for (size_t x = 0; x < nv; ++x) first[x + 1] += first[x];
  std::vector<int> at_vertex(2 * edges.size()), fill(first.begin(), first.end() - 1);
  for (int e = 0; e < int(edges.size()); ++e) {
    at_vertex[size_t(fill[size_t(edges[size_t(e)].first)]++)] = e;
    at_vertex[size_t(fill[size_t(edges[size_t(e)].second)]++)] = e;
  }
  auto degree = [&](int x) { return first[size_t(x) + 1] - first[size_t(x)]; };
  std::vector<char> used(edges.size(), 0);
  // A polyline from `start` along edge e, through vertices where two lines meet, until a
  // junction, an end or the start again.
  auto walk = [&](int start, int e) {
    std::vector<int> line{start};
    int cur = start;
    used[size_t(e)] = 1;
    while (true) {
      cur = edges[size_t(e)].first == cur ? edges[size_t(e)].second : edges[size_t(e)].first;
      line.push_back(cur);
      if (degree(cur) != 2 || cur == start) break;
      const int* two = &at_vertex[size_t(first[size_t(cur)])];
      const int next = two[0] == e ? two[1] : two[0];
      if (used[size_t(next)]) break;
      used[size_t(next)] = 1;
      e = next;
    }
    const bool closed = line.front() == line.back() && line.size() > 2;
    if (closed) line.pop_back();
    r.lines.push_back(line);
    r.line_closed.push_back(closed);
  };
  // Open lines and lines between junctions first, then closed loops.
  for (int pass = 0; pass < 2; ++pass)
    for (int x = 0; x < int(nv); ++x) {
      if (pass == 0 && degree(x) == 2) continue;
      for (int k = first[size_t(x)]; k < first[size_t(x) + 1]; ++k)
        if (!used[size_t(at_vertex[size_t(k)])]) walk(x, at_vertex[size_t(k)]);
    }
}

/// Ends a SideWorker's serving when the step that uses it is over (or failed).
struct StopWhenDone {
  std::shared_ptr<SideWorker> worker;
  ~StopWhenDone() { worker->stop(); }
};

/// Steps 1-8 on bodies that passed the validation (but for self-intersections, which
/// are being checked beside it).
void unite_valid_bodies(const std::vector<Body>& bodies, const Params& params, Result& r,
                        SelfIntersectionCheck* check) {
  Soup soup;
  soup.body_count = int(bodies.size());
  for (int b = 0; b < soup.body_count; ++b) {
    const int base = int(soup.vertex.size());
    soup.vertex.insert(soup.vertex.end(), bodies[b].vertices.begin(), bodies[b].vertices.end());
    for (const auto& f : bodies[b].faces) {
      soup.face.push_back({f[0] + base, f[1] + base, f[2] + base});
      soup.body.push_back(b);
    }
  }
  PointTable pts;
  // Room for about one crossing per two faces (sphere clusters make ~0.45): growing
  // a table of hundreds of thousands of points rehashes it at cache-miss speed.
  pts.reserve(soup.vertex.size() + soup.face.size() / 2);
  std::vector<int> vertex_point(soup.vertex.size());
  for (size_t v = 0; v < soup.vertex.size(); ++v) vertex_point[v] = pts.insert(make_point(soup.vertex[v]));
  const int input_points = pts.size();

  // 1. Candidate pairs.
  auto t = Clock::now();
  auto pairs = candidate_pairs(soup);
  r.candidate_pairs = int(pairs.size());
  r.time_pairs_ms = ms_since(t);

  // 2. Exact intersections.
  t = Clock::now();
  CutFaces cf(soup.face.size());
  PairIntersector intersector(soup, pts, vertex_point);
  intersector.reserve(pairs.size() / 4);  // crossings: ~1/5 of the pairs
  std::set<std::pair<int, int>> body_pairs;
  std::vector<PairIntersector::Candidate> may_meet = intersector.prepare(pairs);
  for (const auto& candidate : may_meet) {
    const auto [f, g] = pairs[size_t(candidate.pair)];
    if (intersector.intersect(pairs[size_t(candidate.pair)], candidate, cf)) {
      ++r.intersecting_face_pairs;
      body_pairs.insert({std::min(soup.body[f], soup.body[g]), std::max(soup.body[f], soup.body[g])});
    }
  }
  r.intersecting_pairs = int(body_pairs.size());
  r.time_intersect_ms = ms_since(t);

  // 3. Re-triangulation of the cut faces; coplanar duplicates are marked.
  t = Clock::now();
  std::vector<std::array<int, 3>> sub;
  std::vector<int> sub_body, sub_face;
  std::vector<char> sub_cut;  // from a face that was cut
  sub.reserve(soup.face.size() + 8 * cf.size());
  std::vector<char> dropped;
  std::vector<int> kept_copy_body;  // for a dropped same-side copy: the body whose copy stays
  auto corners_of = [&](int f) {
    return std::array<int, 3>{vertex_point[soup.face[f][0]], vertex_point[soup.face[f][1]], vertex_point[soup.face[f][2]]};
  };
  // The cut faces are triangulated in parallel (the point table is only read), then
  // committed in face order, which makes the table and the output independent of it.
  std::vector<int> cut_list;
  for (int f = 0; f < int(soup.face.size()); ++f)
    if (cf.find(f)) cut_list.push_back(f);
  std::vector<FaceTriangles> cut_triangles(cut_list.size());
  parallel_for(cut_list.size(), 64, [&](size_t k) {
    const int f = cut_list[k];
    triangulate_face(pts, corners_of(f), *cf.find(f), cut_triangles[k]);
  });
  size_t next_cut = 0;
  for (int f = 0; f < int(soup.face.size()); ++f) {
    const std::array<int, 3> corners = corners_of(f);
    const FaceConstraints* it = cf.find(f);
    const size_t first = sub.size();
    if (!it) sub.push_back(corners);
    else {
      commit_face(pts, cut_triangles[next_cut], sub);
      FaceTriangles().triangles.swap(cut_triangles[next_cut].triangles);  // freed as it goes
      ++next_cut;
      ++r.cut_faces;
    }
    for (size_t s = first; s < sub.size(); ++s) {
      sub_body.push_back(soup.body[f]);
      sub_face.push_back(f);
      sub_cut.push_back(it != nullptr);
      char drop = 0;
      int copy_body = -1;
      if (it && !it->coplanar.empty()) {
        const Projection pr = face_projection(pts[corners[0]], pts[corners[1]], pts[corners[2]]);
        for (int g : it->coplanar) {
          if (!inside_coplanar(pts, vertex_point, soup, g, sub[s], pr)) continue;
          const auto& G = soup.face[g];
          const bool same = orient2d(pts[vertex_point[G[0]]], pts[vertex_point[G[1]]], pts[vertex_point[G[2]]], pr.i,
                                     pr.j) > 0;
          // Opposite sides: solid on both sides, both copies go. Same side: both stay
          // through the fill, which always prefers the lower body's copy where they
          // coincide, so the higher body's copy is never reached (dropping it before the
          // fill would leave edges where only some copies of a partly overlapping pair
          // are missing, and the fill could not tell the sheets apart there).
          if (!same) drop = 1;
          else if (soup.body[g] < soup.body[f]) copy_body = soup.body[g];
        }
      }
      dropped.push_back(drop);
      kept_copy_body.push_back(copy_body);
    }
  }
  {  // Constructed points that ended up as vertices (some sections built on the way are unused).
    std::vector<char> used(pts.size(), 0);
    for (const auto& t : sub)
      for (int id : t) used[id] = 1;
    for (int id = input_points; id < pts.size(); ++id) r.intersection_points += used[id];
  }
  r.time_retriangulate_ms = ms_since(t);

  // 4. Outside surface.
  t = Clock::now();
  Classification cl = classify_outside(pts, sub, sub_body, sub_face, dropped, kept_copy_body, soup);
  r.orientation_conflicts = cl.orientation_conflicts;
  if (cl.orientation_conflicts > 0)
    throw AlgorithmFailure(
        "the outer surface could not be told apart where coincident faces of different bodies only "
        "partly overlap (" + std::to_string(cl.orientation_conflicts) +
        " ambiguous edges); move one of the touching bodies very slightly and retry");
  if (cl.open_sides > 0)
    throw AlgorithmFailure("the cut surface is not closed at " + std::to_string(cl.open_sides) +
                           " edges (internal error; please report the input)");
  // Output vertices: one per fan of kept faces around a point (so bodies touching
  // along an edge or at a point give a manifold result).
  const int ns = int(sub.size());
  UnionFind uf(3 * ns);
  for (int s = 0; s < ns; ++s) {
    if (!cl.kept[s]) continue;
    for (int z = 0; z < 3; ++z) {
      const int side = cl.partner[3 * s + z];
      if (side < 0) continue;
      const int u = side / 3, y = side % 3;
      // The edge's start corner of s meets the end corner of the partner, and vice versa.
      uf.unite(3 * s + z, 3 * u + (y + 1) % 3);
      uf.unite(3 * s + (z + 1) % 3, 3 * u + y);
    }
  }
  std::vector<int> vertex_of(3 * size_t(ns), -1);
  std::vector<char> cut;
  std::vector<int> face_of_sub(size_t(ns), -1);
  for (int s = 0; s < ns; ++s) {
    if (!cl.kept[s]) continue;
    face_of_sub[size_t(s)] = int(r.faces.size());
    std::array<int, 3> face;
    std::array<bool, 3> line;
    for (int z = 0; z < 3; ++z) {
      const int root = uf.find(3 * s + z);
      if (vertex_of[root] < 0) {
        vertex_of[root] = int(r.vertices.size());
        r.vertices.push_back(pts[sub[s][z]].d);
      }
      face[z] = vertex_of[root];
      line[z] = cl.line_edge[3 * s + z] != 0;
    }
    r.faces.push_back(face);
    r.face_source.push_back(sub_face[s]);
    cut.push_back(sub_cut[s]);
    r.line_edge.push_back(line);
  }
  r.faces_removed = ns - int(r.faces.size());
  {  // Sheets that touch along a segment and meet again at both ends: one edge per sheet.
    const auto doubled = doubled_line_edges(r);
    if (!doubled.empty()) {
      std::vector<int> partner(3 * r.faces.size(), -1);
      for (int s = 0; s < ns; ++s)
        if (cl.kept[s])
          for (int z = 0; z < 3; ++z) {
            const int p = cl.partner[3 * size_t(s) + size_t(z)];
            if (p >= 0 && face_of_sub[size_t(p / 3)] >= 0)
              partner[3 * size_t(face_of_sub[size_t(s)]) + size_t(z)] = 3 * face_of_sub[size_t(p / 3)] + p % 3;
          }
      r.doubled_edges_split = split_doubled_edges(r, cut, std::move(partner), doubled);
    }
  }
  r.rounded_edges_merged = merge_rounded_together(r, cut);
  int flipped = 0;
  r.rounded_caps_split = split_rounded_caps(r, cut, &flipped);
  if (flipped > 0) r.rounded_edges_merged += merge_rounded_together(r, cut);
  r.time_classify_ms = ms_since(t);

  // Nothing above is needed any more. The sliver step runs on this thread; the temporaries
  // are freed on one other thread, which then checks the bodies for self-intersections
  // (a third thread on two cores slowed the sliver step more than the check costs).
  auto free_temporaries = destroyer(soup, pts, vertex_point, pairs, cf, intersector, may_meet, sub, sub_body, sub_face,
                                    sub_cut, dropped, kept_copy_body, cut_list, cut_triangles, cl, uf, vertex_of,
                                    face_of_sub);
  // That thread then serves the sliver step, checking bodies between its tasks (the
  // helper is shared: the thread may reach serve() only after this function returns).
  BackgroundRelease release;
  const auto helper = std::make_shared<SideWorker>();
  const StopWhenDone stop_helper{helper};  // (before `release` joins, and before the check is finished)
  if (check)
    check->start(std::move(free_temporaries), [helper, check] { helper->serve([check] { return check->check_next(); }); });
  else
    release.run(std::move(free_temporaries), [helper] { helper->serve(); });
  // 5. Slivers.
  t = Clock::now();
  // (On one thread nobody serves: the step then checks each move in its plain order.)
  SideWorker* lent = worker_count() > 1 ? helper.get() : nullptr;
  if (params.sliver_angle_deg > 0)
    r.slivers_collapsed = collapse_slivers(r, cut, params.sliver_angle_deg, params.sliver_max_deviation,
                                           params.sliver_max_volume_change, lent, &r.sliver_parts, &r.flat_flips);
  r.time_slivers_ms = ms_since(t);
  for (const auto& l : r.line_edge) r.intersection_edges += int(l[0]) + int(l[1]) + int(l[2]);
  r.intersection_edges /= 2;
  chain_lines(r);
  r.min_angle_deg = min_angle_deg(r.vertices, r.faces);
  r.slivers_left_faces = find_slivers_left(r, bodies, kReportedSliverDeg);
  r.slivers_left = int(r.slivers_left_faces.size());
}

}  // namespace

Result compute_union(const std::vector<Body>& input, const Params& params) {
  const auto t_start = Clock::now();
  if (!(params.sliver_angle_deg >= 0 && params.sliver_angle_deg < 60))
    throw InvalidInput("sliver angle must be in [0, 60) degrees");
  if (!(params.sliver_max_deviation >= 0) || !(params.sliver_max_volume_change >= 0))
    throw InvalidInput("sliver deviation and volume change bounds must be >= 0");
  std::vector<Body> bodies = input;
  Result r;
  r.bodies_reoriented = validate_bodies(bodies);
  r.bodies = int(bodies.size());
  // Declared after `bodies`, so it is joined before they go. Started beside the sliver
  // step; the steps before it only cut and sort faces, which a body crossing itself
  // cannot derail (a failure there waits for the check, whose message is the one given).
  std::optional<SelfIntersectionCheck> check;
  if (params.check_self_intersections) check.emplace(bodies);
  try {
    unite_valid_bodies(bodies, params, r, check ? &*check : nullptr);
  } catch (...) {
    if (check) check->finish();  // a body crossing itself explains any failure: said first
    throw;
  }
  if (check) check->finish();
  r.time_total_ms = ms_since(t_start);
  return r;
}

Body body_from_mesh(const TriMesh& mesh, const std::string& name) {
  Body b;
  b.name = name;
  std::vector<int> index(mesh.vert.size(), -1);
  for (size_t i = 0; i < mesh.vert.size(); ++i) {
    if (mesh.vert[i].IsD()) continue;
    index[i] = int(b.vertices.size());
    const auto& p = mesh.vert[i].cP();
    b.vertices.push_back({p[0], p[1], p[2]});
  }
  for (const auto& f : mesh.face) {
    if (f.IsD()) continue;
    b.faces.push_back({index[vcg::tri::Index(mesh, f.cV(0))], index[vcg::tri::Index(mesh, f.cV(1))],
                       index[vcg::tri::Index(mesh, f.cV(2))]});
  }
  return b;
}

std::vector<Body> bodies_from_components(const TriMesh& mesh, std::vector<std::vector<int>>* mesh_faces) {
  // Faces connected through shared vertices form one component.
  const int nv = int(mesh.vert.size());
  UnionFind uf(nv);
  for (const auto& f : mesh.face) {
    if (f.IsD()) continue;
    for (int z = 1; z < 3; ++z) uf.unite(int(vcg::tri::Index(mesh, f.cV(0))), int(vcg::tri::Index(mesh, f.cV(z))));
  }
  std::map<int, int> body_of_root;
  std::vector<Body> bodies;
  if (mesh_faces) mesh_faces->clear();
  std::vector<int> local(nv, -1);
  for (const auto& f : mesh.face) {
    if (f.IsD()) continue;
    const int root = uf.find(int(vcg::tri::Index(mesh, f.cV(0))));
    auto [it, added] = body_of_root.emplace(root, int(bodies.size()));
    if (added) {
      bodies.emplace_back();
      bodies.back().name = "component " + std::to_string(it->second);
      if (mesh_faces) mesh_faces->emplace_back();
    }
    if (mesh_faces) (*mesh_faces)[size_t(it->second)].push_back(int(vcg::tri::Index(mesh, &f)));
    Body& b = bodies[it->second];
    std::array<int, 3> face;
    for (int z = 0; z < 3; ++z) {
      const int v = int(vcg::tri::Index(mesh, f.cV(z)));
      if (local[v] < 0) {
        local[v] = int(b.vertices.size());
        const auto& p = mesh.vert[v].cP();
        b.vertices.push_back({p[0], p[1], p[2]});
      }
      face[z] = local[v];
    }
    b.faces.push_back(face);
  }
  return bodies;
}

void to_tri_mesh(const Result& r, TriMesh& out) {
  out.Clear();
  vcg::tri::Allocator<TriMesh>::AddVertices(out, r.vertices.size());
  vcg::tri::Allocator<TriMesh>::AddFaces(out, r.faces.size());
  for (size_t i = 0; i < r.vertices.size(); ++i) out.vert[i].P() = Point3(r.vertices[i][0], r.vertices[i][1], r.vertices[i][2]);
  for (size_t f = 0; f < r.faces.size(); ++f)
    for (int z = 0; z < 3; ++z) {
      out.face[f].V(z) = &out.vert[r.faces[f][z]];
      if (r.line_edge[f][z]) out.face[f].SetFaceEdgeS(z);
    }
  vcg::tri::UpdateBounding<TriMesh>::Box(out);
}

}  // namespace mr::surface_union
