// Carries the bodies' per-face and per-vertex colour and quality over to the union layer,
// and records each face's body, from where the core says each element lies on the input
// (filters/union/source_attributes.h). Only the MeshLab side lives here.
#pragma once

#include <common/ml_document/mesh_model.h>

#include "union/source_attributes.h"

#include <vector>

namespace mr::union_plugin {

/// One body as it came from a MeshLab mesh: the mesh and, per body face, its index in `mesh->cm.face`.
struct BodySource {
  const MeshModel* mesh = nullptr;
  std::vector<int> face;
};

struct Transfer {
  bool face_color = false, face_quality = false, vertex_color = false, vertex_quality = false;
};

/// Each face's body, and where the union's faces and vertices lie on the input when a face
/// or vertex attribute is asked for: computed before the layer is made, so that a failure
/// changes nothing.
struct Origins {
  std::vector<int> body;
  std::vector<surface_union::FaceOrigin> faces;
  std::vector<surface_union::PointOrigin> vertices;
};
Origins find_origins(const surface_union::Result& r, const std::vector<surface_union::Body>& bodies,
                     const Transfer& what);

/// Writes into `layer` (holding the union's faces and vertices in order): the per-face
/// attribute "body" (the body index), and what `what` asks for. A source mesh without the
/// attribute gives grey (128, 128, 128) or 0, as MeshLab's own Boolean filters do. Faces
/// take their source face's value, vertices the values of its source face's corners at
/// their barycentric coordinates.
void transfer_attributes(const Origins& origins, const std::vector<BodySource>& sources, const Transfer& what,
                         MeshModel& layer);

}  // namespace mr::union_plugin
