#include "filter_heal_patch_gaps.h"

#include "common/error_translation.h"
#include "healing/patch_healing.h"

#include <QElapsedTimer>

#include <cmath>

namespace {
constexpr const char* kFilter = "meshing_heal_patch_gaps";
}

FilterHealPatchGapsPlugin::FilterHealPatchGapsPlugin() {
  typeList = {FP_HEAL_PATCH_GAPS};
  for (ActionIDType t : types()) actionList.push_back(new QAction(filterName(t), this));
}

QString FilterHealPatchGapsPlugin::pluginName() const { return "MeshRegridHealing"; }

QString FilterHealPatchGapsPlugin::filterName(ActionIDType) const {
  return "Heal Gaps, Overlaps and T-Junctions between Patches (MeshRegrid)";
}

QString FilterHealPatchGapsPlugin::pythonFilterName(ActionIDType) const { return kFilter; }

QString FilterHealPatchGapsPlugin::filterInfo(ActionIDType) const {
  return "Closes the gaps, overlaps and T-junctions between surface patches that should share their "
         "borders (CAD exports). Border vertices of different patches closer than the vertex tolerance "
         "are matched; a border vertex near the middle of another border edge splits that edge; border "
         "edges whose ends match are paired when they are within the edge tolerance, moved to their "
         "average and welded. Orientation is made consistent (outward for closed parts). What stays open "
         "is selected (faces and vertices) and the widest gap is reported. Welded borders sharper than the "
         "feature angle become feature lines (per-face-edge selection) and patches are grouped into "
         "regions bounded by them (face attribute <code>group_id</code> and colour).<br>"
         "The result goes to a new layer; the input is not modified. Vertex quality holds how far each "
         "vertex moved.<br>"
         "For more details see:<br>"
         "<b>M. Uva, G. Monno, B. Hamann</b><br>"
         "'A New Method for the Repair of CAD Data with Discontinuities', 1999";
}

FilterPlugin::FilterClass FilterHealPatchGapsPlugin::getClass(const QAction*) const {
  return FilterPlugin::Cleaning;
}

int FilterHealPatchGapsPlugin::getPreConditions(const QAction*) const { return MeshModel::MM_NONE; }

int FilterHealPatchGapsPlugin::postCondition(const QAction*) const { return MeshModel::MM_NONE; }

RichParameterList FilterHealPatchGapsPlugin::initParameterList(const QAction*, const MeshModel& m) {
  const Scalarm diag = m.cm.bbox.Diag();
  mr::healing::Params defaults;
  RichParameterList list;
  list.addParam(RichEnum("patch_source", COMPONENTS,
                         {"Connected components", "Face attribute patch_id", "Visible layers"}, "Patches",
                         "What a patch is: a connected component of the current mesh (faces sharing vertices), "
                         "the faces with one value of the per-face attribute patch_id (e.g. from Select "
                         "Feature Lines and Surface Patches), or each visible layer."));
  list.addParam(RichPercentage("vertex_tolerance", diag * Scalarm(0.001), 0, diag, "Vertex tolerance",
                               "Border vertices of different patches closer than this are matched, and a border "
                               "vertex closer than this to another border edge splits it. No vertex moves "
                               "further than this."));
  list.addParam(RichPercentage("edge_tolerance", 0, 0, diag, "Edge tolerance",
                               "A pair of border edges is welded only if every point of one is within this "
                               "distance of the other. 0 uses the vertex tolerance."));
  list.addParam(RichFloat("feature_angle", defaults.feature_angle_deg, "Feature angle (deg)",
                          "A welded patch border is a feature line when the normals across it differ by more "
                          "than this angle; feature lines bound the groups."));
  list.addParam(RichBool("orient_outward", defaults.orient_outward, "Orient closed parts outward",
                         "After making the orientation consistent, turn closed parts so their normals point out."));
  list.addParam(RichBool("color_groups", true, "Colour faces by group", "Give each group its own face colour."));
  return list;
}

namespace {

/// The live vertices and faces of the layers, as the core takes them.
struct Patches {
  std::vector<mr::Point3> points;
  std::vector<std::array<int, 3>> faces;
  std::vector<int> face_patch;
};

/// Appends `src`'s live faces with patch label `patch` (or the patch_id
/// attribute when `patch < 0`).
void append_patches(const CMeshO& src, int patch, Patches& out) {
  std::vector<int> index(src.vert.size(), -1);
  for (size_t v = 0; v < src.vert.size(); ++v) {
    if (src.vert[v].IsD()) continue;
    index[v] = int(out.points.size());
    const auto& p = src.vert[v].cP();
    out.points.emplace_back(p[0], p[1], p[2]);
  }
  auto attr = patch < 0 ? vcg::tri::Allocator<CMeshO>::FindPerFaceAttribute<Scalarm>(const_cast<CMeshO&>(src), "patch_id")
                        : CMeshO::PerFaceAttributeHandle<Scalarm>();
  // An attribute of that name but another type (a point attribute, say) gives
  // an invalid handle: reading through it would crash the host.
  if (patch < 0 && !vcg::tri::Allocator<CMeshO>::IsValidHandle(src, attr))
    throw MLException(QString("%1: the per-face attribute patch_id is not a scalar attribute; store one "
                              "number per face (e.g. with Select Feature Lines and Surface Patches)").arg(kFilter));
  for (size_t f = 0; f < src.face.size(); ++f) {
    const CFaceO& face = src.face[f];
    if (face.IsD()) continue;
    out.faces.push_back({index[vcg::tri::Index(src, face.cV(0))], index[vcg::tri::Index(src, face.cV(1))],
                         index[vcg::tri::Index(src, face.cV(2))]});
    if (patch >= 0) {
      out.face_patch.push_back(patch);
    } else {
      const Scalarm id = attr[f];
      if (!std::isfinite(double(id)) || std::abs(double(id)) > 1e9)
        throw MLException(QString("%1: the patch_id attribute has a NaN, infinite or huge value (face %2)")
                              .arg(kFilter).arg(f));
      out.face_patch.push_back(int(std::lround(double(id))));
    }
  }
}

void write_layer(const mr::healing::Result& r, MeshModel& layer, bool color_groups) {
  CMeshO& cm = layer.cm;
  cm.Clear();
  vcg::tri::Allocator<CMeshO>::AddVertices(cm, r.points.size());
  vcg::tri::Allocator<CMeshO>::AddFaces(cm, r.faces.size());
  layer.updateDataMask(MeshModel::MM_VERTQUALITY | MeshModel::MM_FACECOLOR);
  for (size_t v = 0; v < r.points.size(); ++v) {
    cm.vert[v].P() = Point3m(r.points[v][0], r.points[v][1], r.points[v][2]);
    cm.vert[v].Q() = Scalarm(r.vertex_move[v]);
  }
  auto group = vcg::tri::Allocator<CMeshO>::GetPerFaceAttribute<Scalarm>(cm, "group_id");
  auto patch = vcg::tri::Allocator<CMeshO>::GetPerFaceAttribute<Scalarm>(cm, "patch_id");
  const int groups = std::max(r.groups, 1);
  for (size_t f = 0; f < r.faces.size(); ++f) {
    CFaceO& face = cm.face[f];
    for (int z = 0; z < 3; ++z) face.V(z) = &cm.vert[r.faces[f][z]];
    group[face] = Scalarm(r.face_group[f]);
    patch[face] = Scalarm(r.face_patch[f]);
    if (color_groups) face.C() = vcg::Color4b::Scatter(groups, r.face_group[f]);
    for (int z = 0; z < 3; ++z) {
      if (r.feature[f][z]) face.SetFaceEdgeS(z);
      if (r.open_border[f][z]) {  // what stays open is selected, so the user sees it
        face.SetS();
        face.V(z)->SetS();
        face.V((z + 1) % 3)->SetS();
      }
    }
  }
  vcg::tri::UpdateSelection<CMeshO>::FaceCount(cm);  // keeps the selection counters in step
  vcg::tri::UpdateSelection<CMeshO>::VertexCount(cm);
  vcg::tri::UpdateBounding<CMeshO>::Box(cm);
  vcg::tri::UpdateNormal<CMeshO>::PerVertexNormalizedPerFace(cm);
}

}  // namespace

std::map<std::string, QVariant> FilterHealPatchGapsPlugin::applyFilter(
    const QAction*, const RichParameterList& params, MeshDocument& md, unsigned int&, vcg::CallBackPos* cb) {
  QElapsedTimer timer;
  timer.start();
  MeshModel* current = md.mm();
  if (current == nullptr) throw MLException(QString("%1: there is no current mesh").arg(kFilter));

  const int source = params.getEnum("patch_source");
  Patches input;
  QString label = current->label();
  if (source == VISIBLE_LAYERS) {
    int layer = 0, used = 0;
    for (MeshModel& m : md.meshIterator()) {
      if (m.isVisible() && m.cm.fn > 0) { append_patches(m.cm, layer, input); ++used; }
      ++layer;
    }
    if (used == 0) throw MLException(QString("%1: no visible layer has faces").arg(kFilter));
    label = "patches";
  } else {
    if (current->cm.fn == 0)
      throw MLException(QString("%1: the current mesh has no faces (a point cloud?): this filter needs "
                                "triangle patches").arg(kFilter));
    if (source == PATCH_ID_ATTRIBUTE &&
        !vcg::tri::HasPerFaceAttribute(current->cm, std::string("patch_id")))
      throw MLException(QString("%1: the current mesh has no per-face attribute patch_id; run Select Feature "
                                "Lines and Surface Patches first or use connected components").arg(kFilter));
    append_patches(current->cm, source == PATCH_ID_ATTRIBUTE ? -1 : 0, input);
    if (source == COMPONENTS) input.face_patch.clear();  // the core finds the components
  }

  mr::healing::Params p;
  p.vertex_tolerance = params.getAbsPerc("vertex_tolerance");
  p.edge_tolerance = params.getAbsPerc("edge_tolerance");
  p.feature_angle_deg = params.getFloat("feature_angle");
  p.orient_outward = params.getBool("orient_outward");

  if (cb) cb(10, "Pairing patch borders");
  const mr::healing::Result r = mr::bridge::run_core(kFilter, [&] { return mr::healing::heal(std::move(input.points), std::move(input.faces), std::move(input.face_patch), p); });
  if (cb) cb(90, "Writing the healed layer");
  MeshModel* layer = md.addNewMesh("", label + " healed", true);
  write_layer(r, *layer, params.getBool("color_groups"));

  const double ms = double(timer.nsecsElapsed()) * 1e-6;
  log("Healing: %d patches, %d border pairs welded, %d T-junctions split, %d -> %d boundary edges, "
      "largest move %g, largest gap left %g, %d groups (%.1f ms)",
      r.patches_in, r.borders_paired, r.t_junctions_split, r.boundary_edges_before, r.boundary_edges_after,
      r.largest_move, r.largest_gap, r.groups, ms);
  return {
      {"patches", QVariant(r.patches_in)},
      {"borders_paired", QVariant(r.borders_paired)},
      {"pairs_rejected", QVariant(r.pairs_rejected)},
      {"t_junctions_split", QVariant(r.t_junctions_split)},
      {"vertices_moved", QVariant(r.vertices_moved)},
      {"largest_move", QVariant(r.largest_move)},
      {"boundary_edges_before", QVariant(r.boundary_edges_before)},
      {"boundary_edges_after", QVariant(r.boundary_edges_after)},
      {"non_manifold_edges_after", QVariant(r.non_manifold_edges_after)},
      {"open_loops", QVariant(r.open_loops)},
      {"gaps_left", QVariant(r.gaps_left)},
      {"largest_gap", QVariant(r.largest_gap)},
      {"duplicate_faces_removed", QVariant(r.duplicate_faces_removed)},
      {"faces_flipped", QVariant(r.faces_flipped)},
      {"orientation_conflicts", QVariant(r.orientation_conflicts)},
      {"feature_edges", QVariant(r.feature_edges)},
      {"groups", QVariant(r.groups)},
      {"time_ms", QVariant(ms)},
  };
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterHealPatchGapsPlugin)
