#include "filter_interpolatory_quad.h"

#include "common/error_translation.h"
#include "common/mesh_bridge.h"
#include "quadsub/interpolatory_subdivision.h"

#include <QElapsedTimer>

#include <cmath>

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
         "sharper than the crease angle, stay sharp. The result is a new layer of quads (faux diagonals).<br>"
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

RichParameterList FilterInterpolatoryQuadPlugin::initParameterList(const QAction*, const MeshModel&) {
  mr::quadsub::Params d;
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

  if (cb) cb(0, "Reading polygons");
  mr::bridge::CoreCopy copy;
  mr::bridge::copy_to_core(model->cm, copy);
  const char* name = "meshing_surface_subdivision_interpolatory_quad";
  const mr::quadsub::Result r = mr::bridge::run_core(name, [&] {
    std::vector<mr::Point3> points;
    for (const auto& v : copy.mesh.vert) points.push_back(v.cP());
    const auto polygons = copy.mesh.face.empty() ? std::vector<std::vector<int>>{}
                                                 : mr::quadsub::polygons_from_faux_edges(copy.mesh);
    mr::quadsub::EdgeList creases;
    if (use_selection)
      for (const auto& f : copy.mesh.face)
        for (int z = 0; z < 3; ++z)
          if (f.IsFaceEdgeS(z) && !f.IsF(z))
            creases.push_back({int(vcg::tri::Index(copy.mesh, f.cV(z))), int(vcg::tri::Index(copy.mesh, f.cV((z + 1) % 3)))});
    if (cb) cb(20, "Subdividing");
    return mr::quadsub::subdivide(points, polygons, creases, p);
  });
  if (cb) cb(90, "Writing the new layer");
  mr::TriMesh out;
  mr::quadsub::quads_to_tri_mesh(r.mesh, out);
  MeshModel* layer = md.addNewMesh("", model->label() + " interpolatory quad", true);
  mr::bridge::copy_from_core(out, layer->cm);
  layer->updateDataMask(MeshModel::MM_POLYGONAL);
  vcg::tri::UpdateNormal<CMeshO>::PerVertexNormalizedPerFaceNormalized(layer->cm);

  const double ms = double(timer.nsecsElapsed()) * 1e-6;
  log("Interpolatory quad subdivision: %d polygons -> %d quads in %d levels (%.1f ms)", r.faces_in,
      int(r.mesh.quads.size()), r.levels, ms);
  return {
      {"vertices_in", QVariant(r.vertices_in)},
      {"faces_in", QVariant(r.faces_in)},
      {"vertices_out", QVariant(int(r.mesh.points.size()))},
      {"faces_out", QVariant(int(r.mesh.quads.size()))},
      {"extraordinary_vertices", QVariant(r.extraordinary_vertices)},
      {"crease_edges", QVariant(r.crease_edges_in)},
      {"levels", QVariant(r.levels)},
      {"time_ms", QVariant(ms)},
  };
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterInterpolatoryQuadPlugin)
