#include "filter_remesh.h"

#include "common/error_translation.h"
#include "common/mesh_bridge.h"
#include "remesh/remesh.h"
#include "remesh/wedge_tips.h"

#include <QElapsedTimer>

#include <cmath>

Remeshing::Remeshing() {
  typeList = {FP_ADVANCING_FRONT_REMESH};
  for (ActionIDType t : types()) actionList.push_back(new QAction(filterName(t), this));
}

QString Remeshing::pluginName() const { return "MeshRegridRemesh"; }

QString Remeshing::filterName(ActionIDType) const { return "Remeshing: Advancing Front (MeshRegrid)"; }

QString Remeshing::pythonFilterName(ActionIDType) const { return "meshing_advancing_front_remesh"; }

QString Remeshing::filterInfo(ActionIDType) const {
  return "Regrids a triangulated surface with an advancing front that works directly on the input "
         "triangles. Feature lines (ridges by the ridge angle, boundaries, non-manifold edges) are found "
         "first; corners are kept as output vertices at the same position and each line is re-discretised "
         "with the element size, its points lying on the input polyline. Every surface patch between the "
         "lines is then filled by a front that adds the smallest new face first, places a new point for a "
         "well-shaped triangle (projected onto the input), prefers existing front points nearby and rejects "
         "triangles crossing the front in the tangent plane. A post-pass of edge swaps and smoothing only "
         "raises angles. The result goes to a new layer; the input is not modified.<br>"
         "For more details see:<br>"
         "<b>R. Löhner</b><br>"
         "<a href=\"https://doi.org/10.1006/jcph.1996.0001\">'Regridding Surface Triangulations'</a><br>"
         "Journal of Computational Physics, Volume 126, Issue 1, 1996";
}

FilterPlugin::FilterClass Remeshing::getClass(const QAction*) const { return FilterPlugin::Remeshing; }

int Remeshing::getPreConditions(const QAction*) const { return MeshModel::MM_NONE; }

int Remeshing::postCondition(const QAction*) const { return MeshModel::MM_NONE; }

RichParameterList Remeshing::initParameterList(const QAction*, const MeshDocument& md) {
  mr::remesh::Params d;
  const MeshModel* m = md.mm();
  const double diag = m != nullptr ? double(m->cm.bbox.Diag()) : 1.0;
  RichParameterList list;
  list.addParam(RichPercentage("target_length", Scalarm(diag * 0.01), 0, Scalarm(diag), "Target edge length",
                               "Element size: absolute, or a percentage of the bounding-box diagonal (default 1%). "
                               "Must be > 0 and below the diagonal."));
  list.addParam(RichFloat("ridge_angle", Scalarm(d.ridge_angle_deg), "Ridge angle (deg)",
                          "An edge is a feature ridge, kept exactly, when its face normals differ by more than "
                          "this angle, in (0, 180). Boundary and non-manifold edges are always ridges."));
  list.addParam(RichFloat("corner_angle", Scalarm(d.corner_angle_deg), "Corner angle (deg)",
                          "A point on two ridges is a corner, kept as an output vertex, when the line turns by "
                          "more than this angle, in [0, 180]."));
  list.addParam(RichPercentage("min_line_length", Scalarm(diag * 0.02), 0, Scalarm(diag), "Minimum feature line length",
                               "Feature-noise suppression: ridge lines shorter than this with an open end, "
                               "closed ridge loops shorter than this and the borders of small sliver patches "
                               "are not kept as features (elements of the "
                               "target size cannot represent them). Set it to twice the target length (the default is "
                               "twice the default target, 2% of the diagonal); 0 keeps every ridge and corner."));
  list.addParam(RichPercentage("max_surface_error", 0, 0, Scalarm(diag), "Max surface (chord) error",
                               "Curvature adaptation: where the surface bends, elements shrink so the chord error "
                               "stays below this distance (h <= sqrt(8 e R)). 0 keeps the size uniform."));
  list.addParam(RichFloat("gradation", Scalarm(d.gradation), "Size gradation",
                          "Sizes change by at most (gradation - 1) times the distance, so they vary smoothly; >= 1."));
  list.addParam(RichEnum("recovery", 0, {"Linear (as is)", "Closest input vertex", "Quadratic", "Cubic"},
                         "Surface recovery",
                         "Where free points go after meshing: kept on the input triangles, moved to the closest "
                         "input vertex, or onto a quadratic (Hermite mid-sides from vertex normals) or cubic "
                         "(from positions and normals) surface through the input. Feature points never move."));
  list.addParam(RichInt("improvement_iterations", d.improvement_iterations, "Improvement sweeps",
                        "Sweeps of edge swaps and smoothing that only raise the minimum angle (0 = off)."));
  list.addParam(RichBool("use_selected_edges_as_ridges", d.use_selected_edges_as_ridges, "Keep selected edges as ridges",
                         "Also keep the current per-face-edge selection as feature lines (e.g. the intersection "
                         "lines a union selects), besides the edges the ridge angle finds."));
  list.addParam(RichBool("relax_wedges", d.relax_wedges, "Relax narrow wedges",
                         "Where two feature lines leave a point at under 30 degrees, the face between them keeps "
                         "that angle as long as both lines are kept. With this on, the two lines share their first "
                         "segment there (their first points merge, halfway between them on the surface or else at one "
                         "of them, when they are at most 0.6 x the size apart and the merge raises the smallest "
                         "angle): near the tip each line moves by at most the points' distance, half of it where "
                         "they meet halfway. Lines that pass closer than 0.25 x the size without meeting, where a "
                         "face between them stays under 30 degrees, are made to meet there the same way (two "
                         "points merge, or a point joins the other line's segment it faces)."));
  list.addParam(RichBool("use_size_source", false, "Use a size source layer",
                         "Limit the size near the vertices of another layer, each vertex carrying the wanted size "
                         "in its vertex quality."));
  list.addParam(RichMesh("size_source", m != nullptr ? m->id() : 0, &md, "Size source layer",
                         "Layer whose vertices are point sources and whose edges (an edge mesh) are line sources; vertex "
                         "quality holds the size (absolute), interpolated along the edges."));
  return list;
}

std::map<std::string, QVariant> Remeshing::applyFilter(const QAction*, const RichParameterList& params,
                                                       MeshDocument& md, unsigned int&, vcg::CallBackPos* cb) {
  QElapsedTimer timer;
  timer.start();
  const char* name = "meshing_advancing_front_remesh";
  MeshModel* model = md.mm();
  if (model == nullptr) throw MLException(QString(name) + ": there is no current mesh");

  mr::remesh::Params p;
  p.target_length = params.getAbsPerc("target_length");
  p.ridge_angle_deg = params.getFloat("ridge_angle");
  p.corner_angle_deg = params.getFloat("corner_angle");
  p.min_line_length = params.getAbsPerc("min_line_length");
  // The core reads a negative length as "the target length" (its Python default); here a
  // negative value can only be a mistake.
  if (p.min_line_length < 0)
    throw MLException(QString(name) + ": min_line_length must be >= 0 (0 keeps every ridge)");
  p.max_surface_error = params.getAbsPerc("max_surface_error");
  p.gradation = params.getFloat("gradation");
  const int recovery = params.getEnum("recovery");
  if (recovery < 0 || recovery > 3) throw MLException(QString(name) + ": recovery must be 0..3");
  p.recovery = mr::remesh::Recovery(recovery);
  p.improvement_iterations = params.getInt("improvement_iterations");
  p.use_selected_edges_as_ridges = params.getBool("use_selected_edges_as_ridges");
  p.relax_wedges = params.getBool("relax_wedges");
  if (params.getBool("use_size_source")) {
    const MeshModel* source = md.getMesh(params.getMeshId("size_source"));
    if (source == nullptr) throw MLException(QString(name) + ": the size source layer does not exist");
    if (!source->hasDataMask(MeshModel::MM_VERTQUALITY))
      throw MLException(QString(name) + ": the size source layer has no vertex quality; store the wanted size there");
    std::vector<int> index(source->cm.vert.size(), -1);
    for (size_t i = 0; i < source->cm.vert.size(); ++i) {
      const auto& v = source->cm.vert[i];
      if (v.IsD()) continue;
      if (!(v.cQ() > 0) || !std::isfinite(double(v.cQ())))
        throw MLException(QString(name) + ": every size source vertex needs a quality (size) > 0");
      index[i] = int(p.source_points.size());
      p.source_points.push_back(mr::Point3(v.cP()[0], v.cP()[1], v.cP()[2]));
      p.source_sizes.push_back(double(v.cQ()));
    }
    // Edges of the layer (an edge mesh, e.g. the feature filter's lines layer) are line sources.
    for (const auto& e : source->cm.edge) {
      if (e.IsD()) continue;
      const int a = index[vcg::tri::Index(source->cm, e.cV(0))], b = index[vcg::tri::Index(source->cm, e.cV(1))];
      if (a >= 0 && b >= 0 && a != b) p.source_segments.push_back({a, b});
    }
  }
  if (cb) p.progress = [cb](int percent, const char* what) { cb(percent, what); };

  mr::bridge::CoreCopy copy;
  mr::bridge::copy_to_core(model->cm, copy);
  mr::TriMesh output;
  // The new layer is created only after the core succeeded, so a failure changes nothing.
  const mr::remesh::Result r =
      mr::bridge::run_core(name, [&] { return mr::remesh::remesh(copy.mesh, p, output); });
  MeshModel* layer = md.addNewMesh("", model->label() + " remeshed", true);
  mr::bridge::copy_from_core(output, layer->cm);
  auto kind = vcg::tri::Allocator<CMeshO>::GetPerVertexAttribute<Scalarm>(layer->cm, "point_kind");
  for (size_t i = 0; i < output.vert.size(); ++i) {
    if (output.vert[i].IsS()) layer->cm.vert[i].SetS();
    kind[layer->cm.vert[i]] = Scalarm(output.vert[i].cQ());
  }
  layer->updateBoxAndNormals();

  const double ms = double(timer.nsecsElapsed()) * 1e-6;
  log("Advancing front: %d vertices, %d faces, min angle %.2f deg, %d unmeshed front sides (%.1f ms)",
      int(output.vert.size()), int(output.face.size()), r.min_angle_deg, r.unmeshed_sides, ms);
  if (r.wedge_tips > 0)
    log("%d face corners lie at the tip of a wedge between two feature lines under %.0f deg (the narrowest "
        "%.2f deg): no mesh keeping the lines does better there (relax_wedges lets them share a first "
        "segment); every other corner is %.2f deg or more",
        r.wedge_tips, mr::remesh::kWedgeBoundDeg, r.min_wedge_angle_deg, r.min_angle_off_wedges_deg);
  if (r.kept_crumples)
    log("Meshed again keeping the crumpled patches%s: the first meshing left front sides open or points "
        "not manifold",
        r.kept_folded_slivers ? " and the sliver patches bordered by folds" : "");
  if (r.non_manifold_points > 0)
    log("%d points are not manifold (their faces make more than one fan)", r.non_manifold_points);
  if (r.flat_pockets_removed > 0)
    log("%d pairs of faces on the same three points, facing apart, removed: a patch folded onto itself "
        "closed the same triangle from both sides",
        r.flat_pockets_removed);
  if (r.missing_feature_edges > 0)
    log("%d feature line segments are no output edge: the faces closed over a line's end that lies a hair "
        "beside another line",
        r.missing_feature_edges);
  return {
      {"vertices", QVariant(int(output.vert.size()))},
      {"faces", QVariant(int(output.face.size()))},
      {"corners", QVariant(r.corners)},
      {"lines", QVariant(r.lines)},
      {"patches", QVariant(r.patches)},
      {"suppressed_lines", QVariant(r.suppressed_lines)},
      {"feature_edges", QVariant(r.feature_edges)},
      {"min_angle", QVariant(r.min_angle_deg)},
      {"mean_min_angle", QVariant(r.mean_min_angle_deg)},
      {"wedge_tips", QVariant(r.wedge_tips)},
      {"min_wedge_angle", QVariant(r.min_wedge_angle_deg)},
      {"min_angle_off_wedges", QVariant(r.min_angle_off_wedges_deg)},
      {"edges_in_range", QVariant(r.edges_in_range)},
      {"hausdorff", QVariant(r.hausdorff)},
      {"hausdorff_rel", QVariant(r.diagonal > 0 ? r.hausdorff / r.diagonal : 0.0)},
      {"unmeshed_sides", QVariant(r.unmeshed_sides)},
      {"unmeshed_patches", QVariant(r.unmeshed_patches)},
      {"bounded_patches", QVariant(r.bounded_patches)},
      {"missing_feature_edges", QVariant(r.missing_feature_edges)},
      {"flat_pockets_removed", QVariant(r.flat_pockets_removed)},
      {"line_points_removed", QVariant(r.line_points_removed)},
      {"relaxed_wedges", QVariant(r.relaxed_wedges)},
      {"closed_line_gaps", QVariant(r.closed_line_gaps)},
      {"jointly_moved", QVariant(r.jointly_moved)},
      {"kept_folded_slivers", QVariant(r.kept_folded_slivers)},
      {"kept_crumples", QVariant(r.kept_crumples)},
      {"non_manifold_points", QVariant(r.non_manifold_points)},
      {"retried_patches", QVariant(r.retried_patches)},
      {"local_repairs", QVariant(r.local_repairs)},
      {"remeshed_off_lines", QVariant(r.remeshed_off_lines)},
      {"merged_lines", QVariant(r.merged_lines)},
      {"merged_corners", QVariant(r.merged_corners)},
      {"thin_patches", QVariant(r.thin_patches)},
      {"thin_step_faces", QVariant(r.thin_step_faces)},
      {"narrow_rim_faces", QVariant(r.narrow_rim_faces)},
      {"neck_points", QVariant(r.neck_points)},
      {"swaps", QVariant(r.swaps)},
      {"smoothed", QVariant(r.smoothed)},
      {"collapsed", QVariant(r.collapsed)},
      {"split", QVariant(r.split)},
      {"snapped", QVariant(r.snapped)},
      {"surface_swaps", QVariant(r.surface_swaps)},
      {"target_length", QVariant(p.target_length)},
      {"time_ms", QVariant(ms)},
  };
}

MESHLAB_PLUGIN_NAME_EXPORTER(Remeshing)
