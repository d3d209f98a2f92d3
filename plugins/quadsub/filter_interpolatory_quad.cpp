#include "filter_interpolatory_quad.h"

#include "common/error_translation.h"
#include "common/mesh_bridge.h"
#include "quadsub/adaptive_refinement.h"
#include "quadsub/interpolatory_subdivision.h"

#include <QElapsedTimer>

#include <cmath>
#include <string>

FilterInterpolatoryQuadPlugin::FilterInterpolatoryQuadPlugin() {
  typeList = {FP_INTERPOLATORY_QUAD};
  for (ActionIDType t : types()) actionList.push_back(new QAction(filterName(t), this));
}

QString FilterInterpolatoryQuadPlugin::pluginName() const { return "MeshRegridInterpolatoryQuad"; }

QString FilterInterpolatoryQuadPlugin::filterName(ActionIDType) const {
  return "Subdivision Surfaces: Interpolatory Quad (MeshRegrid)";
}

QString FilterInterpolatoryQuadPlugin::pythonFilterName(ActionIDType) const {
  return "meshing_surface_subdivision_interpolatory_quad";
}

QString FilterInterpolatoryQuadPlugin::filterInfo(ActionIDType) const {
  return "Refines a quad mesh (or any polygon mesh: other polygons are first split into quads around "
         "their centroid) by an interpolatory scheme: every old vertex stays where it is and the limit "
         "surface is smooth. Edge points use the 4-point rule with tension w "
         "(e = (8+w)/16 (p0+q0) - w/16 (p*+q*)); face points apply the same rule to the new edge points; "
         "at extraordinary vertices a virtual point replaces the missing neighbour. Boundaries use the "
         "curve rule on boundary vertices only, with reflection at corners; selected edges, or edges "
         "sharper than the crease angle, stay sharp; selected vertices can be cusps. Adaptive refinement "
         "splits only the selected faces, or the faces whose face point lies farther than a threshold from "
         "their bilinear centre; faces sharing an edge differ by at most one level and hanging points are "
         "closed by transition quads and triangles, so the result has no cracks. The result is a new layer "
         "of quads (faux diagonals), plus transition triangles when adaptive, with the per-face attribute "
         "<code>subdivision_level</code>.<br>"
         "For more details see:<br>"
         "<b>L. Kobbelt, T. Hesse, H. Prautzsch, K. Schweizerhof</b><br>"
         "<a href=\"https://doi.org/10.1108/02644409710170339\">'Iterative Mesh Generation for FE-Computations "
         "on Free Form Surfaces'</a><br>Engineering Computations, Volume 14, Issue 7, 1997";
}

FilterPlugin::FilterClass FilterInterpolatoryQuadPlugin::getClass(const QAction*) const {
  return FilterClass(FilterPlugin::Remeshing | FilterPlugin::Polygonal);
}

int FilterInterpolatoryQuadPlugin::getPreConditions(const QAction*) const { return MeshModel::MM_NONE; }

int FilterInterpolatoryQuadPlugin::postCondition(const QAction*) const { return MeshModel::MM_NONE; }

RichParameterList FilterInterpolatoryQuadPlugin::initParameterList(const QAction*, const MeshModel& m) {
  mr::quadsub::Params d;
  mr::quadsub::AdaptiveParams a;
  const double diag = m.cm.bbox.IsNull() ? 1.0 : double(m.cm.bbox.Diag());
  RichParameterList list;
  list.addParam(RichInt("iterations", d.iterations, "Iterations",
                        "Number of subdivision steps, 1 to 8; each step multiplies the quads by 4."));
  list.addParam(RichFloat("w", d.w, "Tension w",
                          "Tension of the 4-point rule, in [0, sqrt(5)-1 = 1.236]. 1 reproduces cubic "
                          "polynomials; 0 gives midpoints (bilinear)."));
  list.addParam(RichFloat("crease_angle", d.crease_angle_deg, "Crease angle (deg)",
                          "Edges whose two quads meet at more than this angle, in degrees, stay sharp. "
                          "0 turns angle creases off."));
  list.addParam(RichBool("use_selected_edges_as_creases", false, "Keep selected edges sharp",
                         "Treat the current per-face-edge selection as creases."));
  list.addParam(RichFloat("corner_angle", d.corner_angle_deg, "Corner angle (deg)",
                          "A boundary or crease that turns by more than this angle, in degrees, is a corner "
                          "(reflection rule)."));
  list.addParam(RichBool("use_selected_vertices_as_cusps", false, "Selected vertices are cusps",
                         "The surface comes to a point at each selected vertex (the tip of a cone, a hole shrunk "
                         "to a point): every edge through it keeps its own direction there."));
  list.addParam(RichEnum("adaptive", 0, {"All faces", "Selected faces", "Faces above error threshold"},
                         "Refine",
                         "Which faces each step splits: all (uniform); the selected faces (a polygon is selected "
                         "when any of its triangles is) and, at later steps, their children; or the faces whose "
                         "new face point lies farther than the error threshold from the mean of their corners. "
                         "Faces sharing an edge never differ by more than one level (coarser neighbours are split "
                         "first) and transition faces close the hanging points."));
  list.addParam(RichPercentage("error_threshold", Scalarm(diag * a.error_threshold), 0, Scalarm(diag),
                               "Error threshold",
                               "With 'Faces above error threshold': a face is split when its face point lies "
                               "farther than this from its bilinear centre; absolute, or a percentage of the "
                               "bounding-box diagonal (default 0.1%). Must be > 0."));
  return list;
}

std::map<std::string, QVariant> FilterInterpolatoryQuadPlugin::applyFilter(
    const QAction*, const RichParameterList& params, MeshDocument& md, unsigned int&, vcg::CallBackPos* cb) {
  QElapsedTimer timer;
  timer.start();
  MeshModel* model = md.mm();
  if (model == nullptr) throw MLException("meshing_surface_subdivision_interpolatory_quad: there is no current mesh");
  mr::quadsub::Params p;
  p.iterations = params.getInt("iterations");
  p.w = params.getFloat("w");
  p.crease_angle_deg = params.getFloat("crease_angle");
  p.corner_angle_deg = params.getFloat("corner_angle");
  const bool use_selection = params.getBool("use_selected_edges_as_creases");
  const bool use_cusps = params.getBool("use_selected_vertices_as_cusps");
  const int refine = params.getEnum("adaptive");
  if (refine < 0 || refine > 2)
    throw MLException("meshing_surface_subdivision_interpolatory_quad: adaptive must be 0 (all faces), "
                      "1 (selected faces) or 2 (faces above error threshold)");
  mr::quadsub::AdaptiveParams ap;
  ap.refine = refine == 0   ? mr::quadsub::RefineFaces::All
              : refine == 1 ? mr::quadsub::RefineFaces::Selected
                            : mr::quadsub::RefineFaces::ErrorAbove;
  const double diag = model->cm.bbox.IsNull() ? 0.0 : double(model->cm.bbox.Diag());
  ap.error_threshold = diag > 0 ? params.getAbsPerc("error_threshold") / diag : 0.0;

  if (cb) cb(0, "Reading polygons");
  mr::bridge::CoreCopy copy;
  mr::bridge::copy_to_core(model->cm, copy);
  const char* name = "meshing_surface_subdivision_interpolatory_quad";
  const mr::quadsub::AdaptiveResult r = mr::bridge::run_core(name, [&] {
    std::vector<mr::Point3> points;
    for (const auto& v : copy.mesh.vert) points.push_back(v.cP());
    std::vector<int> polygon_of_face;
    const auto polygons = copy.mesh.face.empty() ? std::vector<std::vector<int>>{}
                                                 : mr::quadsub::polygons_from_faux_edges(copy.mesh, &polygon_of_face);
    std::vector<char> selected(polygons.size(), 0);
    for (size_t f = 0; f < copy.mesh.face.size(); ++f)
      if (copy.mesh.face[f].IsS()) selected[polygon_of_face[f]] = 1;
    if (use_cusps)
      for (size_t v = 0; v < copy.mesh.vert.size(); ++v)
        if (copy.mesh.vert[v].IsS()) p.cusp_vertices.push_back(int(v));
    mr::quadsub::EdgeList creases;
    if (use_selection)
      for (const auto& f : copy.mesh.face)
        for (int z = 0; z < 3; ++z)
          if (f.IsFaceEdgeS(z) && !f.IsF(z))
            creases.push_back({int(vcg::tri::Index(copy.mesh, f.cV(z))), int(vcg::tri::Index(copy.mesh, f.cV((z + 1) % 3)))});
    if (cb) cb(20, "Subdividing");
    return mr::quadsub::subdivide_adaptive(points, polygons, creases, selected, p, ap);
  });
  if (cb) cb(90, "Writing the new layer");
  mr::TriMesh out;
  mr::quadsub::quads_to_tri_mesh(r.mesh, r.triangles, out);
  MeshModel* layer = md.addNewMesh("", model->label() + " interpolatory quad", true);
  mr::bridge::copy_from_core(out, layer->cm);
  layer->updateDataMask(MeshModel::MM_POLYGONAL);
  auto level_attr = vcg::tri::Allocator<CMeshO>::GetPerFaceAttribute<Scalarm>(layer->cm, "subdivision_level");
  const size_t quad_faces = 2 * r.mesh.quads.size();
  for (size_t f = 0; f < layer->cm.face.size(); ++f)
    level_attr[f] = Scalarm(f < quad_faces ? r.quad_level[f / 2] : r.triangle_level[f - quad_faces]);
  vcg::tri::UpdateNormal<CMeshO>::PerVertexNormalizedPerFaceNormalized(layer->cm);

  const double ms = double(timer.nsecsElapsed()) * 1e-6;
  log("Interpolatory quad subdivision: %d polygons -> %d quads and %d triangles, up to level %d (%.1f ms)",
      r.faces_in, int(r.mesh.quads.size()), int(r.triangles.size()), r.levels, ms);
  std::map<std::string, QVariant> out_values = {
      {"vertices_in", QVariant(r.vertices_in)},
      {"faces_in", QVariant(r.faces_in)},
      {"vertices_out", QVariant(int(r.mesh.points.size()))},
      {"faces_out", QVariant(int(r.mesh.quads.size() + r.triangles.size()))},
      {"quads_out", QVariant(int(r.mesh.quads.size()))},
      {"triangles_out", QVariant(int(r.triangles.size()))},
      {"extraordinary_vertices", QVariant(r.extraordinary_vertices)},
      {"crease_edges", QVariant(r.crease_edges_in)},
      {"cusps", QVariant(r.cusps)},
      {"levels", QVariant(r.levels)},
      {"balance_refinements", QVariant(r.balance_refinements)},
      {"transition_faces", QVariant(r.transition_faces)},
      {"time_ms", QVariant(ms)},
  };
  for (size_t l = 0; l < r.refined_per_level.size(); ++l)
    out_values["faces_refined_level_" + std::to_string(l)] = QVariant(r.refined_per_level[l]);
  return out_values;
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterInterpolatoryQuadPlugin)
