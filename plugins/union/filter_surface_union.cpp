#include "filter_surface_union.h"

#include "common/error_translation.h"
#include "common/mesh_bridge.h"
#include "union_attributes.h"
#include "union/surface_union.h"

#include <QElapsedTimer>

namespace {
constexpr const char* kName = "generate_surface_intersection_union";
}

FilterSurfaceUnionPlugin::FilterSurfaceUnionPlugin() {
  typeList = {FP_SURFACE_INTERSECTION_UNION};
  for (ActionIDType t : types()) actionList.push_back(new QAction(filterName(t), this));
}

QString FilterSurfaceUnionPlugin::pluginName() const { return "MeshRegridSurfaceUnion"; }

QString FilterSurfaceUnionPlugin::filterName(ActionIDType) const {
  return "Union of Intersecting Closed Surfaces (MeshRegrid)";
}

QString FilterSurfaceUnionPlugin::pythonFilterName(ActionIDType) const { return kName; }

QString FilterSurfaceUnionPlugin::filterInfo(ActionIDType) const {
  return "Computes the outer surface of the union of many closed triangulated bodies at once, "
         "directly on their triangulations. The bodies are either all visible layers or the connected "
         "components of the current mesh.<br>"
         "Candidate face pairs come from a uniform grid; triangle-triangle intersections are decided by "
         "exact orientation predicates (floating-point filter, exact rational fallback), so coplanar faces, "
         "shared vertices and edges, and touching bodies are handled. Intersection points are exact and "
         "shared by all faces that contain them. Each cut face is re-triangulated in its plane with the "
         "intersection segments as constraints; the outer surface is collected by a flood fill from an "
         "extreme face that, at intersection edges, continues into the neighbour visible from the current face. "
         "Slivers left by the cut are removed by collapsing their shortest edge when no normal flips and the "
         "quality improves; the input's own slivers on flat faces (CAD needles) are flipped towards the "
         "Delaunay triangulation of their plane, which moves no point.<br>"
         "The result is a new layer, watertight, manifold and consistently oriented, with the intersection "
         "lines as the per-face-edge selection; optionally a second layer holds the lines as an edge mesh. "
         "Faces under 5 degrees that are worse than the input face they lie in (slivers the step could not "
         "mend, counted in slivers_left) are selected, so they can be seen.<br>"
         "For more details see:<br>"
         "<b>A. Shostko, R. Löhner, W. Sandberg</b><br>"
         "<a href=\"https://doi.org/10.1002/(SICI)1097-0207(19990410)44:10%3C1359::AID-NME544%3E3.0.CO;2-B\">"
         "'Surface triangulation over intersecting geometries'</a><br>"
         "International Journal for Numerical Methods in Engineering, Volume 44, Issue 9, 1999";
}

FilterPlugin::FilterClass FilterSurfaceUnionPlugin::getClass(const QAction*) const {
  return FilterPlugin::FilterClass(FilterPlugin::MeshCreation | FilterPlugin::Remeshing);
}

int FilterSurfaceUnionPlugin::getPreConditions(const QAction*) const { return MeshModel::MM_NONE; }

int FilterSurfaceUnionPlugin::postCondition(const QAction*) const { return MeshModel::MM_NONE; }

RichParameterList FilterSurfaceUnionPlugin::initParameterList(const QAction*, const MeshModel&) {
  mr::surface_union::Params defaults;
  RichParameterList list;
  list.addParam(RichEnum("bodies", VISIBLE_LAYERS,
                         QStringList() << "All visible layers" << "Connected components of the current mesh",
                         "Bodies",
                         "Which closed bodies to unite: every visible layer is one body, or every connected "
                         "component of the current mesh is one body."));
  list.addParam(RichFloat("sliver_angle", defaults.sliver_angle_deg, "Sliver angle (deg)",
                          "After the cut, faces with an angle below this (degrees, [0, 60)) are removed by "
                          "collapsing their shortest edge when that improves quality, flips no normal and keeps "
                          "the intersection lines; the input's own such faces on flat parts are flipped within their "
                          "plane (no point moves). 0 turns the step off."));
  list.addParam(RichFloat("sliver_max_deviation", defaults.sliver_max_deviation, "Sliver collapse deviation",
                          "Largest distance the sliver step may move the surface from the exact union, all its "
                          "moves together, as a fraction of the bounding-box diagonal (checked at samples of "
                          "every face it makes; moves that would move it more are skipped)."));
  list.addParam(RichFloat("sliver_max_volume_change", defaults.sliver_max_volume_change,
                          "Sliver collapse volume change",
                          "Bound on the volume change of the sliver step that its moves could not give back "
                          "(collapses, flips and relocations move a nearby vertex to keep the volume), as a "
                          "fraction of the volume of the union."));
  list.addParam(RichBool("check_self_intersections", defaults.check_self_intersections,
                         "Refuse bodies that cross themselves",
                         "Check every body for faces that cross each other (exactly) and stop with a message "
                         "naming the body. Off: such a body gives an undefined result; faster on inputs known "
                         "to be clean (convex bodies cost almost nothing either way)."));
  list.addParam(RichBool("create_lines_layer", false, "Create a layer with the intersection lines",
                         "Add a new layer holding the intersection lines as an edge mesh (polylines)."));
  // The same names and meaning as MeshLab's own Boolean filters (vertices interpolated here).
  list.addParam(RichBool("transfer_face_color", false, "Transfer face color",
                         "Give each face of the union the color of the input face it lies in."));
  list.addParam(RichBool("transfer_face_quality", false, "Transfer face quality",
                         "Give each face of the union the quality of the input face it lies in."));
  list.addParam(RichBool("transfer_vert_color", false, "Transfer vertex color",
                         "Give each vertex of the union the color of the input at its place: an input "
                         "vertex's own, or, for intersection points and moved vertices, the colors of the "
                         "input face's corners weighted by the vertex's barycentric coordinates there."));
  list.addParam(RichBool("transfer_vert_quality", false, "Transfer vertex quality",
                         "Give each vertex of the union the quality of the input at its place (interpolated "
                         "like the vertex color)."));
  return list;
}

namespace {

void add_lines_layer(MeshDocument& md, const mr::surface_union::Result& r) {
  MeshModel* layer = md.addNewMesh("", "union intersection lines", false);
  CMeshO& em = layer->cm;
  std::vector<int> local(r.vertices.size(), -1);
  auto vertex = [&](int v) {
    if (local[v] < 0) {
      local[v] = int(em.vert.size());
      auto it = vcg::tri::Allocator<CMeshO>::AddVertices(em, 1);
      it->P() = Point3m(r.vertices[v][0], r.vertices[v][1], r.vertices[v][2]);
    }
    return local[v];
  };
  for (size_t l = 0; l < r.lines.size(); ++l) {
    const auto& line = r.lines[l];
    const size_t n = line.size();
    const size_t segments = r.line_closed[l] ? n : n - 1;
    for (size_t k = 0; k < segments; ++k) {
      const int a = vertex(line[k]), b = vertex(line[(k + 1) % n]);
      CEdgeO& e = *vcg::tri::Allocator<CMeshO>::AddEdges(em, 1);
      e.V(0) = &em.vert[a];
      e.V(1) = &em.vert[b];
    }
  }
  vcg::tri::UpdateBounding<CMeshO>::Box(em);
}

}  // namespace

std::map<std::string, QVariant> FilterSurfaceUnionPlugin::applyFilter(const QAction*, const RichParameterList& params,
                                                                      MeshDocument& md, unsigned int&,
                                                                      vcg::CallBackPos* cb) {
  QElapsedTimer timer;
  timer.start();
  mr::surface_union::Params p;
  p.sliver_angle_deg = params.getFloat("sliver_angle");
  p.sliver_max_deviation = params.getFloat("sliver_max_deviation");
  p.sliver_max_volume_change = params.getFloat("sliver_max_volume_change");
  p.check_self_intersections = params.getBool("check_self_intersections");
  const int source = params.getEnum("bodies");

  if (cb) cb(0, "Collecting bodies");
  std::vector<mr::surface_union::Body> bodies;
  // Where each body's faces are in its mesh. (The document keeps its meshes in a list:
  // adding the union layer leaves these pointers valid.)
  std::vector<mr::union_plugin::BodySource> sources;
  if (source == CONNECTED_COMPONENTS) {
    MeshModel* model = md.mm();
    if (model == nullptr) throw MLException(QString(kName) + ": there is no current mesh");
    if (model->cm.fn == 0)
      throw MLException(QString(kName) + ": the current mesh '" + model->label() + "' has no faces");
    mr::bridge::CoreCopy copy;
    mr::bridge::copy_to_core(model->cm, copy);
    std::vector<std::vector<int>> core_faces;
    bodies = mr::surface_union::bodies_from_components(copy.mesh, &core_faces);
    for (const auto& list : core_faces) {
      sources.push_back({model, {}});
      for (int f : list) sources.back().face.push_back(copy.source_face[size_t(f)]);
    }
  } else {
    for (MeshModel& m : md.meshIterator()) {
      if (!m.isVisible()) continue;
      mr::bridge::CoreCopy copy;
      mr::bridge::copy_to_core(m.cm, copy);
      bodies.push_back(mr::surface_union::body_from_mesh(copy.mesh, m.label().toStdString()));
      sources.push_back({&m, copy.source_face});  // the body's faces are the copy's, in order
    }
  }
  if (cb) cb(10, "Intersecting, re-triangulating and classifying");
  // Everything is computed before any layer is touched, so an error changes nothing.
  const mr::surface_union::Result r =
      mr::bridge::run_core(kName, [&] { return mr::surface_union::compute_union(bodies, p); });
  mr::union_plugin::Transfer transfer;
  transfer.face_color = params.getBool("transfer_face_color");
  transfer.face_quality = params.getBool("transfer_face_quality");
  transfer.vertex_color = params.getBool("transfer_vert_color");
  transfer.vertex_quality = params.getBool("transfer_vert_quality");
  const auto origins =
      mr::bridge::run_core(kName, [&] { return mr::union_plugin::find_origins(r, bodies, transfer); });
  if (cb) cb(90, "Writing the union layer");
  MeshModel* layer = md.addNewMesh("", "union", true);
  mr::TriMesh out;
  mr::surface_union::to_tri_mesh(r, out);
  mr::bridge::copy_from_core(out, layer->cm);
  for (int f : r.slivers_left_faces) layer->cm.face[size_t(f)].SetS();  // (the core keeps the face order)
  vcg::tri::UpdateSelection<CMeshO>::FaceCount(layer->cm);
  layer->updateBoxAndNormals();
  mr::union_plugin::transfer_attributes(origins, sources, transfer, *layer);
  if (params.getBool("create_lines_layer")) {
    add_lines_layer(md, r);
    md.setCurrentMesh(layer->id());
  }

  const double ms = double(timer.nsecsElapsed()) * 1e-6;
  log("Union of %d bodies: %d intersecting pairs, %d intersection points, %d lines, %d faces removed, "
      "%d slivers collapsed, min angle %.2f deg, %d faces under %.0f deg worse than their input face (%.1f ms)",
      r.bodies, r.intersecting_pairs, r.intersection_points, int(r.lines.size()), r.faces_removed,
      r.slivers_collapsed, r.min_angle_deg, r.slivers_left, mr::surface_union::kReportedSliverDeg, ms);
  return {
      {"bodies", QVariant(r.bodies)},
      {"bodies_reoriented", QVariant(r.bodies_reoriented)},
      {"candidate_pairs", QVariant(r.candidate_pairs)},
      {"intersecting_pairs", QVariant(r.intersecting_pairs)},
      {"intersecting_face_pairs", QVariant(r.intersecting_face_pairs)},
      {"intersection_points", QVariant(r.intersection_points)},
      {"intersection_lines", QVariant(int(r.lines.size()))},
      {"intersection_edges", QVariant(r.intersection_edges)},
      {"cut_faces", QVariant(r.cut_faces)},
      {"faces_removed", QVariant(r.faces_removed)},
      {"slivers_collapsed", QVariant(r.slivers_collapsed)},
      {"flat_flips", QVariant(r.flat_flips)},
      {"orientation_conflicts", QVariant(r.orientation_conflicts)},
      {"doubled_edges_split", QVariant(r.doubled_edges_split)},
      {"rounded_edges_merged", QVariant(r.rounded_edges_merged)},
      {"rounded_caps_split", QVariant(r.rounded_caps_split)},
      {"sliver_parts", QVariant(r.sliver_parts)},
      {"vertices", QVariant(int(r.vertices.size()))},
      {"faces", QVariant(int(r.faces.size()))},
      {"min_angle", QVariant(r.min_angle_deg)},
      {"slivers_left", QVariant(r.slivers_left)},
      {"time_pairs_ms", QVariant(r.time_pairs_ms)},
      {"time_intersect_ms", QVariant(r.time_intersect_ms)},
      {"time_retriangulate_ms", QVariant(r.time_retriangulate_ms)},
      {"time_classify_ms", QVariant(r.time_classify_ms)},
      {"time_slivers_ms", QVariant(r.time_slivers_ms)},
      {"time_ms", QVariant(ms)},
  };
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterSurfaceUnionPlugin)
