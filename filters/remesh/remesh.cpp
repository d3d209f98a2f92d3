#include "remesh/remesh.h"

#include "common/coherent_orientation.h"
#include "common/errors.h"
#include "common/exact_shift.h"
#include "common/mesh_validation.h"
#include "features/feature_lines.h"
#include "remesh/advancing_front.h"
#include "remesh/feature_front.h"
#include "remesh/flat_pockets.h"
#include "remesh/local_repair.h"
#include "remesh/mesh_improvement.h"
#include "remesh/mesh_measures.h"
#include "remesh/neck_caps.h"
#include "remesh/output_mesh.h"
#include "remesh/patch_retry.h"
#include "remesh/size_field.h"
#include "remesh/surface_locator.h"
#include "remesh/surface_recovery.h"
#include "remesh/thin_step_caps.h"
#include "remesh/vertex_snapping.h"
#include "remesh/deviation_swaps.h"

#include <vcg/complex/append.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>

namespace mr::remesh {

namespace {

void check_params(const Params& p, double diagonal) {
  if (!(p.target_length > 0) || !std::isfinite(p.target_length))
    throw InvalidInput("target_length must be > 0, got " + std::to_string(p.target_length) +
                       "; give an absolute length or a percentage of the bounding-box diagonal (1% is typical)");
  if (p.target_length > diagonal)
    throw InvalidInput("target_length " + std::to_string(p.target_length) + " is larger than the model (bounding-box diagonal " +
                       std::to_string(diagonal) + "); choose a length below the diagonal, e.g. 1% of it");
  if (diagonal / p.target_length > 1e5)
    throw InvalidInput("target_length is too small: it would make more than about 10^10 faces; use at least 1e-5 of the diagonal");
  if (!(p.max_surface_error >= 0)) throw InvalidInput("max_surface_error must be >= 0 (0 turns curvature adaptation off)");
  if (!(p.gradation >= 1.0)) throw InvalidInput("gradation must be >= 1, got " + std::to_string(p.gradation));
  if (!std::isfinite(p.min_line_length)) throw InvalidInput("min_line_length must be finite (negative = the target length)");
  if (p.improvement_iterations < 0) throw InvalidInput("improvement_iterations must be >= 0");
  if (p.source_points.size() != p.source_sizes.size()) throw InvalidInput("one size per source point is needed");
  for (size_t i = 0; i < p.source_points.size(); ++i)
    if (!(p.source_sizes[i] > 0) || !std::isfinite(p.source_sizes[i]) || !std::isfinite(p.source_points[i][0]) ||
        !std::isfinite(p.source_points[i][1]) || !std::isfinite(p.source_points[i][2]))
      throw InvalidInput("size source " + std::to_string(i) + " needs a finite position and a size > 0");
  for (const auto& seg : p.source_segments)
    if (seg[0] < 0 || seg[1] < 0 || size_t(seg[0]) >= p.source_points.size() || size_t(seg[1]) >= p.source_points.size())
      throw InvalidInput("a line source refers to a source point that does not exist");
}

void progress(const Params& p, int percent, const char* what) {
  if (p.progress) p.progress(percent, what);
}

void build_output(const OutputMesh& out, const std::vector<std::array<int, 2>>& feature_edges, TriMesh& m) {
  m.Clear();
  // Only points used by a face go out (a point of a line between two unmeshed patches would not).
  std::vector<int> index(out.points.size(), -1);
  int n = 0;
  for (const auto& f : out.faces) for (int v : f) if (index[v] < 0) index[v] = n++;
  auto vi = vcg::tri::Allocator<TriMesh>::AddVertices(m, n);
  (void)vi;
  for (size_t v = 0; v < out.points.size(); ++v)
    if (index[v] >= 0) {
      m.vert[index[v]].P() = out.points[v];
      m.vert[index[v]].Q() = double(int(out.kind[v]));
      if (out.kind[v] == PointKind::Corner) m.vert[index[v]].SetS();
    }
  vcg::tri::Allocator<TriMesh>::AddFaces(m, out.faces.size());
  std::set<std::pair<int, int>> features;
  for (const auto& e : feature_edges) features.insert(std::minmax(e[0], e[1]));
  for (size_t f = 0; f < out.faces.size(); ++f)
    for (int z = 0; z < 3; ++z) {
      const int a = out.faces[f][z], b = out.faces[f][(z + 1) % 3];
      m.face[f].V(z) = &m.vert[index[a]];
      if (features.count(std::minmax(a, b))) m.face[f].SetFaceEdgeS(z);
    }
  m.bbox.SetNull();
  for (const auto& v : m.vert) m.bbox.Add(v.cP());
}

// A feature line shorter than the target size (a short step, a crease between two junctions)
// cannot be meshed well with elements larger than itself: its vertices get its length as size,
// never below kShortLineFloor x target, and the gradation spreads that around it. Which lines:
// those shorter than the target while stage 1 keeps short creases with an open end
// (min_line_length < target; on noisy scans the front needs the refinement there: the strict
// bunny leaves 2 sides unmeshed otherwise); once stage 1 dropped those, only lines shorter than
// kShortLine x target. Measured at 1% with min_line_length = target (rocker-arm, bunny,
// armadillo): edges within [0.7, 1.4] x target 97.0/94.1/86.1% capping every line shorter than
// the target, 98.1/96.5/87.8% at 0.4 x target, 98.7/97.8/93.2% without caps (worst angle bunny
// 6.1 -> 3.1 degrees). Since stage 1 drops sliver patches: 98.4/97.4/89.3% at 0.4, 98.6/97.8/90.5%
// at 0.25 (worst angles and Hausdorff distances unchanged), and without caps the bunny's worst
// angle still falls to 2.9 degrees.
constexpr double kShortLineFloor = 0.5;
constexpr double kShortLine = 0.25;
// The caps grade at 1.6, faster than the field's 1.3: the refinement stays close around the
// short lines. Measured at 1% as above, with stray faces repaired (kStray): armadillo's edges in
// range 85.7 -> 89.2%, its Hausdorff 0.0035 -> 0.0045 of the diagonal (MeshLab 0.0049); bunny
// and rocker-arm keep their worst angles; at 1.8 the bunny's worst fell to 3.4 degrees.
constexpr double kCapGradation = 1.6;
std::vector<double> small_feature_caps(const TriMesh& mesh, const features::Result& fr, double target,
                                       double min_line_length) {
  const double capped_below = min_line_length >= target ? kShortLine * target : target;
  std::vector<double> cap(mesh.vert.size(), 0.0);
  for (const auto& line : fr.lines) {
    double length = 0;
    const size_t n = line.vertices.size();
    for (size_t k = 0; k + 1 < n + (line.closed ? 1 : 0); ++k)
      length += (mesh.vert[line.vertices[k]].cP() - mesh.vert[line.vertices[(k + 1) % n]].cP()).Norm();
    if (length >= capped_below) continue;
    const double h = std::max(length, kShortLineFloor * target);
    for (int v : line.vertices) cap[v] = cap[v] > 0 ? std::min(cap[v], h) : h;
  }
  return cap;
}

// Work bound of the whole run, shared by every front (repairs and retries included): nearby
// points looked at by the candidate checks, per face the size field expects.
constexpr double kChecksPerExpectedFace = 500.0;
long run_check_budget(const Surface& s, const SizeField& size) {
  double faces = 0;
  for (size_t f = 0; f < s.faces.size(); ++f) {
    const auto& t = s.faces[f];
    const double area = 0.5 * ((s.points[t[1]] - s.points[t[0]]) ^ (s.points[t[2]] - s.points[t[0]])).Norm();
    const double h = std::max(size.at(int(f), {1.0 / 3, 1.0 / 3, 1.0 / 3}), 1e-300);
    faces += area / (0.25 * std::sqrt(3.0) * h * h);
  }
  return long(std::min(kChecksPerExpectedFace * (faces + 1000.0), 1e17));
}

// Local repair: the faces within kRepairRadius x target of the open sides, pinched points and
// oversized faces are taken out and the hole is meshed again at kRepairScale x the size, up to
// kRepairRounds times, each around what the last left. A round that does not reduce the trouble,
// breaks an edge or leaks out of its hole is undone. (The 832k armadillo at 1%, one patch: 171
// points of trouble after the front, none after six rounds; whole-patch retries had left 49
// sides open.)
constexpr double kRepairRadius = 2.0;
constexpr double kRepairScale = 0.8;
constexpr int kRepairRounds = 8;
// A face with a side longer than this x target is a stuck front's closure, not an element.
constexpr double kOversized = 2.0;
// ... and so is a needle (an angle under 5 degrees) longer than the target: a point could go in.
// ... and a face whose centroid lies more than this x target off the input: the front bridged a
// groove or cut across a tip (armadillo at 1% with the caps above: 0.0070 -> 0.0043 of the
// diagonal).
constexpr double kStray = 0.5;
constexpr double kNeedleAngle = 5.0 * 3.14159265358979323846 / 180.0;

// Where the front of `patch` went wrong: pinched points and the corners of oversized and stray faces
// (spots), and how much trouble in all: open sides, pinched points and those faces' points.
int trouble(const OutputMesh& out, int patch, const FrontResult& r, const SurfaceLocator& locator, double target,
            std::vector<int>& spots) {
  const std::vector<int> pinched = pinched_points(out, patch);
  spots = oversized_face_points(out, patch, kOversized * target, target, kNeedleAngle);
  const int oversized = int(spots.size());
  spots.insert(spots.end(), pinched.begin(), pinched.end());
  const std::vector<int> stray = stray_face_points(out, patch, locator, kStray * target);
  spots.insert(spots.end(), stray.begin(), stray.end());
  return r.unmeshed_sides + int(pinched.size()) + oversized + int(stray.size());
}

// A repair round or a retry copies and scans the whole output so far: it is charged that
// many checks from the run's budget (with hundreds of broken patches on a damaged input the
// rounds, not the fronts, were what never ended). False: the budget is spent, do not start.
constexpr long kChecksPerWholeMeshElement = 10;  // a hash insert and a copy cost ~10 checks
bool spend_on_whole_mesh(const FrontParams& fp, const OutputMesh& out) {
  if (!fp.checks_left) return true;
  if (*fp.checks_left <= 0) return false;
  *fp.checks_left -= kChecksPerWholeMeshElement * (long(out.faces.size()) + long(out.points.size()));
  return true;
}

FrontResult repair_locally(OutputMesh& out, const std::vector<FrontSide>& initial_front, int patch,
                           const SurfaceLocator& locator, const SizeField& size, const FrontParams& fp,
                           double target, FrontResult r, Result& result) {
  std::vector<int> spots;
  int problems = trouble(out, patch, r, locator, target, spots);
  if (problems > 0 && !spend_on_whole_mesh(fp, out)) return r;
  int bad = problems > 0 ? bad_edges(out) : 0;  // edges with two faces of one orientation or more
  for (int round = 0; round < kRepairRounds && problems > 0; ++round) {
    if (!spend_on_whole_mesh(fp, out)) break;
    OutputMesh saved = out;
    const std::vector<FrontSide> hole =
        open_hole_around(out, patch, initial_front, r.open_sides, spots, kRepairRadius * target);
    const size_t kept = out.faces.size();
    FrontParams hole_params = fp;
    hole_params.meshed_faces = faces_around(out, patch, hole);
    const FrontResult again = advance_front(out, hole, patch, locator, size.scaled(kRepairScale), hole_params);
    std::vector<int> spots_after;
    const int after = trouble(out, patch, again, locator, target, spots_after);
    // A hole front that got out over the mesh around it would make far more faces than it took.
    const bool leaked = again.faces > int(4 * (saved.faces.size() - kept)) + 100;
    const int bad_after = after < problems && !leaked ? bad_edges(out) : bad + 1;
    if (after >= problems || leaked || bad_after > bad) {
      out = std::move(saved);
      break;
    }
    bad = bad_after;
    result.local_repairs++;
    r.unmeshed_sides = again.unmeshed_sides;
    r.open_sides = again.open_sides;
    r.faces += again.faces;
    spots = std::move(spots_after);
    problems = after;
  }
  return r;
}

// A patch whose local repairs left sides open or points pinched is meshed again whole at 0.9 x
// the size, and again at 0.81 x while that helps: each costs a full meshing of the patch (on the
// 832k armadillo, one patch, about 25 s).
constexpr double kRetryScale = 0.9;
constexpr double kMinRetryScale = 0.8;

int open_or_pinched(const OutputMesh& out, int patch, const FrontResult& r) {
  return r.unmeshed_sides + int(pinched_points(out, patch).size());
}

// One patch: the front, local repairs of what it left, then whole-patch retries, each kept only
// when it leaves fewer sides open or points pinched than the mesh before it.
FrontResult mesh_patch(OutputMesh& out, const std::vector<FrontSide>& front, int patch, const SurfaceLocator& locator,
                       const SizeField& size, const FrontParams& fp, double target, Result& result) {
  FrontResult r = advance_front(out, front, patch, locator, size, fp);
  if (fp.thin_patch) {
    // The one layer did not close (an ear it needed was refused): the strip is meshed as any
    // patch, repairs and retries included (fuzz_union --models seed 492: 77 sides left open).
    // Taking its faces out scans the whole output, so it is charged as a retry is.
    if (r.unmeshed_sides == 0 || !spend_on_whole_mesh(fp, out)) return r;
    remove_patch_faces(out, patch);
    FrontParams any = fp;
    any.thin_patch = false;
    return mesh_patch(out, front, patch, locator, size, any, target, result);
  }
  r = repair_locally(out, front, patch, locator, size, fp, target, r, result);
  int open = open_or_pinched(out, patch, r);
  for (double scale = kRetryScale; open > 0 && scale >= kMinRetryScale; scale *= kRetryScale) {
    if (!spend_on_whole_mesh(fp, out)) break;
    OutputMesh saved = out;
    remove_patch_faces(out, patch);
    const SizeField smaller = size.scaled(scale);
    FrontResult again = advance_front(out, front, patch, locator, smaller, fp);
    again = repair_locally(out, front, patch, locator, smaller, fp, target, again, result);
    result.retried_patches++;
    const int open_again = open_or_pinched(out, patch, again);
    if (open_again >= open) {
      out = std::move(saved);
      break;
    }
    r = again;
    open = open_again;
  }
  return r;
}

// The input itself, or, where a careless export flipped some faces, a copy with one orientation
// per part: the host-face search compares normals and the fronts take their direction from the
// faces (half of fandisk's faces flipped at 5%: 88 s and 1010 faces with open sides, instead of
// 0.2 s).
const TriMesh& coherently_oriented(const TriMesh& input, TriMesh& copy) {
  if (count_misoriented_edges(input) == 0) return input;
  vcg::tri::Append<TriMesh, TriMesh>::MeshCopyConst(copy, input);  // flags (selected edges) too
  orient_coherently(copy);
  return copy;
}

/// What stage 1's noise suppression drops of the sliver patches in one regridding.
struct SliverChoice {
  bool drop_crumples = true;
  bool keep_folded_slivers = false;
};

/// One regridding up to its fronts: what finish() needs to complete it. The tries with other
/// sliver choices are compared here, before their post-pass, and only the one kept is
/// finished (box.STL united, at 1%: three tries, of which two were improved, snapped and
/// measured only to be dropped).
struct Fronts {
  Params params;  // the try's own (its progress says which try it is)
  std::optional<Surface> surface;
  std::optional<SizeField> size;
  std::optional<SurfaceLocator> locator;
  OutputMesh out;
  FeatureFront ff;
  Result result;
  int pinched_points = 0;  // points of the fronts' faces that are not manifold
};

/// The regridding up to the fronts, on an input that lies about as close to the origin as it
/// is large.
std::unique_ptr<Fronts> mesh_fronts(const TriMesh& given, const Params& params, SliverChoice choice) {
  auto run = std::make_unique<Fronts>();
  run->params = params;
  Result& result = run->result;
  require_no_duplicate_faces(given);
  require_some_area(given);
  TriMesh oriented;
  const TriMesh& input = coherently_oriented(given, oriented);
  Box3 box;
  for (const auto& v : input.vert) box.Add(v.cP());
  result.diagonal = box.Diag();
  check_params(params, result.diagonal);

  progress(params, 2, "Detecting feature lines and patches");
  features::Params fp;
  fp.ridge_angle_deg = params.ridge_angle_deg;
  fp.corner_angle_deg = params.corner_angle_deg;
  fp.use_selected_edges_as_ridges = params.use_selected_edges_as_ridges;
  fp.min_line_length = params.min_line_length < 0 ? params.target_length : params.min_line_length;
  fp.keep_folded_slivers = choice.keep_folded_slivers;
  fp.drop_crumples = choice.drop_crumples;
  const features::Result fr = features::detect(input, fp);
  result.corners = int(fr.corners.size());
  result.lines = int(fr.lines.size());
  result.patches = fr.patch_count;
  result.suppressed_lines = fr.suppressed_lines;
  result.suppressed_folded_slivers = fr.suppressed_folded_slivers;
  result.suppressed_crumples = fr.suppressed_crumples;

  progress(params, 8, "Building the size field and the surface index");
  const Surface& surface = run->surface.emplace(Surface::from_mesh(input, fr.patch_of_face));
  SizeParams sp;
  sp.target_length = params.target_length;
  sp.max_surface_error = params.max_surface_error;
  sp.gradation = params.gradation;
  sp.source_points = params.source_points;
  sp.source_sizes = params.source_sizes;
  sp.source_segments = params.source_segments;
  sp.vertex_cap = small_feature_caps(input, fr, params.target_length, fp.min_line_length);
  sp.cap_gradation = std::max(kCapGradation, params.gradation);
  // Necks between lines that pass closer than a tenth of the target (neck_caps.h).
  std::vector<double> neck_cap(surface.points.size(), 0.0);
  cap_necks(surface, fr.lines, given_lines(input, fr.lines, params.use_selected_edges_as_ridges), params.target_length,
            neck_cap);
  const SizeField& size = run->size.emplace(size_field_with_steps_and_necks(
      surface, fr.ridge, sp, params.target_length, &result.thin_step_faces, &neck_cap, &result.neck_points,
      &result.narrow_rim_faces));
  const SurfaceLocator& locator = run->locator.emplace(surface, params.target_length);

  progress(params, 12, "Discretising feature lines");
  OutputMesh& out = run->out;
  // Tiny lines merge with the feature-noise suppression on; strict mode keeps every corner.
  const FeatureFront& ff = run->ff = discretise_features(input, fr, surface, size, out, fp.min_line_length > 0);
  result.feature_edges = int(ff.feature_edges.size());

  result.merged_lines = ff.merged_lines;
  result.merged_corners = ff.merged_corners;
  long checks_left = run_check_budget(surface, size);
  std::vector<FrontResult> meshed(size_t(fr.patch_count));
  auto mesh_one = [&](int patch) {
    FrontParams fp_patch;
    fp_patch.checks_left = &checks_left;
    fp_patch.thin_patch = ff.thin_patch[patch] != 0;
    meshed[size_t(patch)] = mesh_patch(out, ff.patch_front[patch], patch, locator, size, fp_patch, params.target_length, result);
  };
  for (int patch = 0; patch < fr.patch_count; ++patch) {
    if (ff.dropped_patch[patch]) continue;  // a sliver between twin lines or inside merged corners
    progress(params, 15 + int(65.0 * patch / std::max(fr.patch_count, 1)), "Advancing the front");
    mesh_one(patch);
  }
  // A patch meshed before the patches beside a line may have joined two points of that line by
  // an edge of its own (two corners joined by a one-segment line, on its border too): the line's
  // patches then gave that edge four faces (fuzz_union --models seed 281). Such a patch is
  // meshed again, the line's segments barred to it.
  const std::vector<int> again = patches_on_taken_lines(out, ff.feature_edges);
  if (!again.empty()) {
    for (const auto& e : ff.feature_edges) out.line_edges.insert(OutputMesh::edge_key(e[0], e[1]));
    for (int patch : again) {
      remove_patch_faces(out, patch);  // (its shared edges rebuilt, the line segments among them)
      mesh_one(patch);
    }
    out.line_edges.clear();
    out.rebuild_shared_edges();
    result.remeshed_off_lines = int(again.size());
  }
  for (int patch = 0; patch < fr.patch_count; ++patch) {
    if (ff.dropped_patch[patch]) continue;
    const FrontResult& r = meshed[size_t(patch)];
    result.thin_patches += ff.thin_patch[patch] ? 1 : 0;
    result.unmeshed_sides += r.unmeshed_sides;
    // (A front stopped at its bound and then closed by the last resort is meshed: it was
    // counted as unmeshed, about 53k patches of a damaged bunny with no side open.)
    if (r.unmeshed_sides > 0) result.unmeshed_patches++;
    if (r.iteration_limit) result.bounded_patches++;
  }

  result.flat_pockets_removed = remove_flat_pockets(out);
  run->pinched_points = count_pinched_points(out);
  return run;
}

/// The post-pass, snapping, recovery and measures of the try kept, into `output`.
Result finish(Fronts& run, TriMesh& output) {
  const Params& params = run.params;
  OutputMesh& out = run.out;
  const FeatureFront& ff = run.ff;
  const SurfaceLocator& locator = *run.locator;
  const SizeField& size = *run.size;
  const Surface& surface = *run.surface;
  Result& result = run.result;

  progress(params, 80, "Improving: swaps and smoothing");
  // (Line points the line does not need may go: the feature edges follow.)
  std::vector<std::array<int, 2>> feature_edges = ff.feature_edges;
  const ImprovementResult ir =
      improve_mesh(out, feature_edges, locator, size, params.improvement_iterations, ff.line_paths, {}, params.relax_wedges);
  result.line_points_removed = ir.line_points_removed;
  result.relaxed_wedges = ir.relaxed_wedges;
  result.closed_line_gaps = ir.closed_line_gaps;
  result.jointly_moved = ir.jointly_moved;
  result.feature_edges = int(feature_edges.size());
  result.swaps = ir.swaps;
  result.smoothed = ir.moves;
  result.collapsed = ir.collapsed;
  result.split = ir.split;

  progress(params, 86, "Snapping to input vertices the output cuts off");
  const std::vector<int> snapped = snap_to_far_vertices(out, locator, size);
  result.snapped = int(snapped.size());
  // Snapping bends the faces around the moved points (armadillo at 1%: 1.4 -> 2.7% of the edges
  // longer than 1.4 x target); the post-pass again around them, with them held on their vertices.
  if (!snapped.empty()) {
    const ImprovementResult again =
        improve_mesh(out, feature_edges, locator, size, params.improvement_iterations, {}, snapped);
    result.swaps += again.swaps;
    result.smoothed += again.moves;
    result.collapsed += again.collapsed;
    result.split += again.split;
    result.jointly_moved += again.jointly_moved;
  }

  // Last, pairs that bridge a crease stage 1 dropped turn to follow it (rocker-arm at 1%: 7 swaps,
  // output-to-input distance 0.00285 -> 0.00259 of the diagonal, angles and lengths unchanged).
  if (params.improvement_iterations > 0)
    result.surface_swaps = swap_towards_surface(out, feature_edges, locator, size);

  progress(params, 88, "Surface recovery");
  recover_surface(out, surface, params.recovery);

  progress(params, 92, "Measuring");
  const Measures m = measure(out, locator, size);
  result.missing_feature_edges = count_missing_edges(out, feature_edges);
  result.non_manifold_points = count_pinched_points(out);
  result.min_angle_deg = m.min_angle_deg;
  const WedgeMeasure wm = measure_wedges(out, feature_edges);
  result.wedge_tips = wm.wedge_tips;
  result.min_wedge_angle_deg = wm.min_wedge_angle_deg;
  result.min_angle_off_wedges_deg = wm.min_angle_off_wedges_deg;
  result.mean_min_angle_deg = m.mean_min_angle_deg;
  result.edges_in_range = m.edges_in_range;
  result.hausdorff = m.hausdorff;
  build_output(out, feature_edges, output);
  progress(params, 100, "Done");
  return result;
}

/// Open sides first, then points that are not manifold: the fewer, the better. (Counted after
/// the fronts: the post-pass has not changed either count on box.STL united or fuzz_union's
/// models seeds 0-47 at 1%, 97 tries, which is what lets the tries be compared before it.)
bool fewer_defects(const Fronts& a, const Fronts& b) {
  return std::make_pair(a.result.unmeshed_sides, a.pinched_points) < std::make_pair(b.result.unmeshed_sides, b.pinched_points);
}

/// The regridding, and where it left sides open or points not manifold, more tries with less
/// of stage 1's noise suppression; the one with the fewest defects stays (the first on a tie).
/// First the crumples it dropped are kept: merged into the side around them, some left that
/// side's front pinched (joint.off united with a copy whose sides coincide with its own, where
/// kept as patches others had been meshed on top of it). Then the sliver patches bordered by
/// folds are kept too: merged across a fold, a patch is one the front cannot mesh (box.STL
/// united, at 1% with the default min_line_length: 19 patches open, then none). A scan's noise
/// has such slivers too, and there dropping them gives better elements: so only as a retry.
Result remesh_near_origin(const TriMesh& given, const Params& params, TriMesh& output) {
  std::unique_ptr<Fronts> best = mesh_fronts(given, params, SliverChoice{});
  auto retry = [&](SliverChoice choice, const char* what) {
    if (best->result.unmeshed_sides == 0 && best->pinched_points == 0) return;
    Params retry_params = params;  // its progress said as such (the bar starts again)
    if (params.progress)
      retry_params.progress = [&params, what](int percent, const char* step) {
        params.progress(percent, (std::string("Meshing again, ") + what + ": " + step).c_str());
      };
    std::unique_ptr<Fronts> again = mesh_fronts(given, retry_params, choice);
    if (!fewer_defects(*again, *best)) return;
    again->result.kept_crumples = true;
    again->result.kept_folded_slivers = choice.keep_folded_slivers;
    best = std::move(again);
  };
  if (best->result.suppressed_crumples > 0) retry(SliverChoice{false, false}, "keeping crumpled patches");
  // (Crumples are folded slivers too: kept already, they need no third meshing.)
  if (best->result.suppressed_folded_slivers > best->result.suppressed_crumples)
    retry(SliverChoice{false, true}, "keeping folded sliver patches");
  return finish(*best, output);
}

/// An output without a face is no result: it is said as an error, so that the caller's
/// document gets no empty layer (a surface flattened onto itself, its two layers folded
/// together, can leave every front open: blade.off flattened across y, found by fuzzing).
void require_some_faces(const TriMesh& output, const Result& r) {
  for (const auto& f : output.face)
    if (!f.IsD()) return;
  throw InvalidInput("no patch could be meshed (" + std::to_string(r.unmeshed_sides) +
                     " front sides stayed open): the input is probably folded or flat, two layers on top of each other");
}

}  // namespace

Result remesh(const TriMesh& given, const Params& params, TriMesh& output) {
  require_triangle_surface(given);  // finite coordinates before the box is taken
  Box3 box;
  for (const auto& v : given.vert) box.Add(v.cP());
  // Far from the origin the tolerances scaled by the element size meet rounding noise
  // (fandisk 1e5 diagonals away left a patch unmeshed); the shift is exact, and the
  // corners and line ends come back bit for bit.
  const Point3 shift = exact_shift_towards_origin(box);
  if (shift == Point3(0, 0, 0)) {
    const Result result = remesh_near_origin(given, params, output);
    require_some_faces(output, result);
    return result;
  }
  TriMesh near;
  vcg::tri::Append<TriMesh, TriMesh>::MeshCopyConst(near, given);  // flags (selected edges) too
  shift_vertices(near, shift);
  Params near_params = params;
  for (auto& p : near_params.source_points) p -= shift;
  const Result result = remesh_near_origin(near, near_params, output);
  shift_vertices(output, -shift);
  require_some_faces(output, result);
  return result;
}

}  // namespace mr::remesh
