#include "filter_feature_lines.h"

#include "common/error_translation.h"
#include "common/mesh_bridge.h"
#include "features/feature_lines.h"

#include <QElapsedTimer>

FilterFeatureLinesPlugin::FilterFeatureLinesPlugin() {
  typeList = {FP_FEATURE_LINES_AND_PATCHES};
  for (ActionIDType t : types()) actionList.push_back(new QAction(filterName(t), this));
}

QString FilterFeatureLinesPlugin::pluginName() const { return "MeshRegridFeatureLines"; }

QString FilterFeatureLinesPlugin::filterName(ActionIDType) const {
  return "Select Feature Lines and Surface Patches (MeshRegrid)";
}

QString FilterFeatureLinesPlugin::pythonFilterName(ActionIDType) const {
  return "compute_feature_lines_and_patches";
}

QString FilterFeatureLinesPlugin::filterInfo(ActionIDType) const {
  return "Finds the feature lines and surface patches of a triangulation.<br>"
         "A <i>ridge</i> is an edge whose two face normals differ by more than the ridge angle; "
         "boundary and non-manifold edges are ridges too. A <i>corner</i> is a vertex on one ridge, on "
         "more than two ridges, or on two ridges that turn by more than the corner angle. "
         "<i>Discrete lines</i> are the chains of ridges between corners (a corner-free ridge loop is "
         "one closed line). <i>Patches</i> are the face regions a flood fill reaches without crossing a ridge.<br>"
         "Ridges become the per-face-edge selection, corners the vertex selection; each face gets the "
         "custom attribute <code>patch_id</code> and one colour per patch. Optionally a new layer holds the "
         "discrete lines as polylines.<br>"
         "For more details see:<br>"
         "<b>R. Löhner</b><br>"
         "<a href=\"https://doi.org/10.1006/jcph.1996.0001\">'Regridding Surface Triangulations'</a><br>"
         "Journal of Computational Physics, Volume 126, Issue 1, 1996";
}

FilterPlugin::FilterClass FilterFeatureLinesPlugin::getClass(const QAction*) const {
  return FilterPlugin::Selection;
}

int FilterFeatureLinesPlugin::getPreConditions(const QAction*) const { return MeshModel::MM_NONE; }

int FilterFeatureLinesPlugin::postCondition(const QAction*) const {
  return MeshModel::MM_FACEFLAGSELECT | MeshModel::MM_VERTFLAGSELECT | MeshModel::MM_FACECOLOR;
}

RichParameterList FilterFeatureLinesPlugin::initParameterList(const QAction*, const MeshModel& m) {
  mr::features::Params defaults;
  const double diag = m.cm.bbox.IsNull() ? 1.0 : double(m.cm.bbox.Diag());
  RichParameterList list;
  list.addParam(RichFloat("ridge_angle", defaults.ridge_angle_deg, "Ridge angle (deg)",
                          "An edge is a ridge when the normals of its two faces differ by more than this "
                          "angle, in degrees, in (0, 180). Boundary and non-manifold edges are always ridges."));
  list.addParam(RichFloat("corner_angle", defaults.corner_angle_deg, "Corner angle (deg)",
                          "A vertex on exactly two ridges is a corner when the line turns there by more "
                          "than this angle, in degrees, in [0, 180]."));
  list.addParam(RichBool("use_selected_edges_as_ridges", defaults.use_selected_edges_as_ridges,
                         "Keep selected edges as ridges",
                         "Also treat the current per-face-edge selection (e.g. from Select Crease Edges) "
                         "as ridges, to add feature lines the angle test misses."));
  list.addParam(RichInt("min_patch_faces", defaults.min_patch_faces, "Minimum patch size (faces)",
                        "Patches with fewer faces merge into their largest neighbouring patch and the "
                        "ridges between them are dropped. 0 turns merging off."));
  list.addParam(RichPercentage("min_line_length", Scalarm(defaults.min_line_length), 0, Scalarm(diag),
                               "Minimum line length",
                               "Feature-noise suppression: lines shorter than this that end in the open (an end "
                               "vertex on that one ridge only), closed ridge loops shorter than this, and the borders "
                               "of sliver patches (area under a tenth of this squared and under 0.02 x their "
                               "border squared, e.g. one thin face whose three edges are ridges) stop being "
                               "ridges, repeatedly; then corners, lines and patches are found again. Absolute, or a "
                               "percentage of the bounding-box diagonal; use the element size you mesh with. "
                               "Boundary, non-manifold and selected edges always stay. 0 keeps every ridge."));
  list.addParam(RichBool("keep_folded_slivers", defaults.keep_folded_slivers, "Keep folded sliver patches",
                         "With the minimum line length: sliver patches bordered by a ridge sharper than 60 "
                         "degrees (a fold) keep their borders. The advancing-front remesher meshes again with "
                         "this on where merging them across the fold left its front open (CAD unions)."));
  list.addParam(RichBool("create_lines_layer", false, "Create a layer with the lines",
                         "Add a new layer holding the discrete lines as an edge mesh (polylines)."));
  list.addParam(RichBool("color_patches", true, "Colour faces by patch",
                         "Give each patch its own face colour."));
  return list;
}

namespace {

void write_results(const mr::bridge::CoreCopy& copy, const mr::features::Result& r, MeshModel& model,
                   bool color_patches) {
  CMeshO& cm = model.cm;
  auto patch_attr = vcg::tri::Allocator<CMeshO>::GetPerFaceAttribute<Scalarm>(cm, "patch_id");
  for (auto& f : cm.face) {
    f.ClearFaceEdgeS(0); f.ClearFaceEdgeS(1); f.ClearFaceEdgeS(2);
  }
  for (size_t j = 0; j < copy.source_face.size(); ++j) {
    CFaceO& f = cm.face[copy.source_face[j]];
    patch_attr[f] = Scalarm(r.patch_of_face[j]);
    for (int z = 0; z < 3; ++z)
      if (r.ridge[j][z]) f.SetFaceEdgeS(z);
  }
  vcg::tri::UpdateSelection<CMeshO>::VertexClear(cm);
  for (int c : r.corners) cm.vert[copy.source_vertex[c]].SetS();
  if (color_patches) {
    model.updateDataMask(MeshModel::MM_FACECOLOR);
    const int n = std::max(r.patch_count, 1);
    for (size_t j = 0; j < copy.source_face.size(); ++j)
      cm.face[copy.source_face[j]].C() = vcg::Color4b::Scatter(n, r.patch_of_face[j]);
  }
}

void add_lines_layer(MeshDocument& md, const MeshModel& source, const mr::bridge::CoreCopy& copy,
                     const mr::features::Result& r) {
  MeshModel* layer = md.addNewMesh("", source.label() + " discrete lines", false);
  CMeshO& em = layer->cm;
  std::vector<int> local(copy.source_vertex.size(), -1);
  for (const auto& line : r.lines) {
    const size_t n = line.vertices.size();
    const size_t segments = line.closed ? n : n - 1;
    for (size_t k = 0; k < segments; ++k) {
      int ends[2] = {line.vertices[k], line.vertices[(k + 1) % n]};
      CEdgeO& e = *vcg::tri::Allocator<CMeshO>::AddEdges(em, 1);
      for (int s = 0; s < 2; ++s) {
        if (local[ends[s]] < 0) {
          local[ends[s]] = int(em.vert.size());
          auto v = vcg::tri::Allocator<CMeshO>::AddVertices(em, 1);
          v->P() = source.cm.vert[copy.source_vertex[ends[s]]].cP();
        }
      }
      e.V(0) = &em.vert[local[ends[0]]];
      e.V(1) = &em.vert[local[ends[1]]];
    }
  }
  vcg::tri::UpdateBounding<CMeshO>::Box(em);
}

}  // namespace

std::map<std::string, QVariant> FilterFeatureLinesPlugin::applyFilter(
    const QAction*, const RichParameterList& params, MeshDocument& md, unsigned int&,
    vcg::CallBackPos* cb) {
  QElapsedTimer timer;
  timer.start();
  MeshModel* model = md.mm();
  if (model == nullptr) throw MLException("compute_feature_lines_and_patches: there is no current mesh");

  mr::features::Params p;
  p.ridge_angle_deg = params.getFloat("ridge_angle");
  p.corner_angle_deg = params.getFloat("corner_angle");
  p.use_selected_edges_as_ridges = params.getBool("use_selected_edges_as_ridges");
  p.min_patch_faces = params.getInt("min_patch_faces");
  p.min_line_length = params.getAbsPerc("min_line_length");
  p.keep_folded_slivers = params.getBool("keep_folded_slivers");

  if (cb) cb(0, "Copying mesh");
  mr::bridge::CoreCopy copy;
  mr::bridge::copy_to_core(model->cm, copy);
  if (cb) cb(20, "Detecting ridges, corners, lines and patches");
  // Everything is computed before the mesh is touched, so an error leaves it unchanged.
  const mr::features::Result r =
      mr::bridge::run_core("compute_feature_lines_and_patches", [&] { return mr::features::detect(copy.mesh, p); });
  if (cb) cb(80, "Writing selections and attributes");
  write_results(copy, r, *model, params.getBool("color_patches"));
  if (params.getBool("create_lines_layer")) add_lines_layer(md, *model, copy, r);

  const double ms = double(timer.nsecsElapsed()) * 1e-6;
  log("Feature lines: %d ridge edges, %d corners, %d lines, %d patches (%.1f ms)", r.ridge_edges,
      int(r.corners.size()), int(r.lines.size()), r.patch_count, ms);
  return {
      {"ridge_edges", QVariant(r.ridge_edges)},
      {"corners", QVariant(int(r.corners.size()))},
      {"lines", QVariant(int(r.lines.size()))},
      {"patches", QVariant(r.patch_count)},
      {"boundary_edges", QVariant(r.boundary_edges)},
      {"non_manifold_edges", QVariant(r.non_manifold_edges)},
      {"merged_patches", QVariant(r.merged_patches)},
      {"suppressed_lines", QVariant(r.suppressed_lines)},
      {"suppressed_ridge_edges", QVariant(r.suppressed_ridge_edges)},
      {"suppressed_folded_slivers", QVariant(r.suppressed_folded_slivers)},
      {"suppressed_crumples", QVariant(r.suppressed_crumples)},
      {"time_ms", QVariant(ms)},
  };
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterFeatureLinesPlugin)
