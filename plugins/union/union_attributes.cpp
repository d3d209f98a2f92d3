#include "union_attributes.h"

#include <cmath>

namespace mr::union_plugin {

namespace {

const vcg::Color4b kGrey(128, 128, 128, 255);

vcg::Color4b weighted(const vcg::Color4b c[3], const std::array<double, 3>& w) {
  vcg::Color4b out;
  for (int k = 0; k < 4; ++k)
    out[k] = (unsigned char)std::lround(std::min(255.0, w[0] * c[0][k] + w[1] * c[1][k] + w[2] * c[2][k]));
  return out;
}

}  // namespace

Origins find_origins(const surface_union::Result& r, const std::vector<surface_union::Body>& bodies,
                     const Transfer& what) {
  Origins o;
  o.body = surface_union::face_bodies(r, bodies);
  if (what.face_color || what.face_quality) o.faces = surface_union::face_origins(r, bodies);
  if (what.vertex_color || what.vertex_quality) o.vertices = surface_union::vertex_origins(r, bodies);
  return o;
}

void transfer_attributes(const Origins& origins, const std::vector<BodySource>& sources, const Transfer& what,
                         MeshModel& layer) {
  CMeshO& out = layer.cm;
  const auto& faces = origins.faces;
  auto source_face = [&](const surface_union::FaceOrigin& o) -> const CFaceO& {
    const BodySource& s = sources[size_t(o.body)];
    return s.mesh->cm.face[size_t(s.face[size_t(o.face)])];
  };
  auto body_of = vcg::tri::Allocator<CMeshO>::GetPerFaceAttribute<Scalarm>(out, "body");
  for (size_t f = 0; f < origins.body.size(); ++f) body_of[out.face[f]] = Scalarm(origins.body[f]);

  if (what.face_color) layer.updateDataMask(MeshModel::MM_FACECOLOR);
  if (what.face_quality) layer.updateDataMask(MeshModel::MM_FACEQUALITY);
  if (what.face_color || what.face_quality)
    for (size_t f = 0; f < faces.size(); ++f) {
      const MeshModel& m = *sources[size_t(faces[f].body)].mesh;
      const CFaceO& sf = source_face(faces[f]);
      if (what.face_color) out.face[f].C() = m.hasDataMask(MeshModel::MM_FACECOLOR) ? sf.cC() : kGrey;
      if (what.face_quality) out.face[f].Q() = m.hasDataMask(MeshModel::MM_FACEQUALITY) ? sf.cQ() : Scalarm(0);
    }

  if (!what.vertex_color && !what.vertex_quality) return;
  if (what.vertex_color) layer.updateDataMask(MeshModel::MM_VERTCOLOR);
  if (what.vertex_quality) layer.updateDataMask(MeshModel::MM_VERTQUALITY);
  const auto& points = origins.vertices;
  for (size_t v = 0; v < points.size(); ++v) {
    const auto& p = points[v];
    const MeshModel& m = *sources[size_t(p.face.body)].mesh;
    const CFaceO& sf = source_face(p.face);
    // The body's corner z is the source face's corner z (bodies keep the meshes' corner order).
    if (what.vertex_color) {
      if (m.hasDataMask(MeshModel::MM_VERTCOLOR)) {
        const vcg::Color4b c[3] = {sf.cV(0)->cC(), sf.cV(1)->cC(), sf.cV(2)->cC()};
        out.vert[v].C() = weighted(c, p.weight);
      } else {
        out.vert[v].C() = kGrey;
      }
    }
    if (what.vertex_quality)
      out.vert[v].Q() = m.hasDataMask(MeshModel::MM_VERTQUALITY)
                            ? Scalarm(p.weight[0] * sf.cV(0)->cQ() + p.weight[1] * sf.cV(1)->cQ() +
                                      p.weight[2] * sf.cV(2)->cQ())
                            : Scalarm(0);
  }
}

}  // namespace mr::union_plugin
