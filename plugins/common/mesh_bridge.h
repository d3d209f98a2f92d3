// Copies between MeshLab's CMeshO and the cores' mr::TriMesh. The cores never
// see MeshLab types; the copy also drops deleted elements so cores get a compact mesh.
#pragma once

#include <common/ml_document/cmesh.h>

#include "common/tri_mesh.h"

#include <vector>

namespace mr::bridge {

/// Live vertices of `src` in order; `vertex_index[i]` is the core index of src.vert[i] (-1 if deleted).
struct CoreCopy {
  TriMesh mesh;
  std::vector<int> vertex_index;
  std::vector<int> face_index;     ///< core index of src.face[i] (-1 if deleted)
  std::vector<int> source_face;    ///< src face index of core face j
  std::vector<int> source_vertex;  ///< src vertex index of core vertex j
};

/// Copies positions, faces and the per-face-edge selection (FaceEdgeS) of the live elements.
inline void copy_to_core(const CMeshO& src, CoreCopy& out) {
  out.vertex_index.assign(src.vert.size(), -1);
  out.face_index.assign(src.face.size(), -1);
  out.source_vertex.clear();
  out.source_face.clear();
  int nv = 0, nf = 0;
  for (size_t i = 0; i < src.vert.size(); ++i)
    if (!src.vert[i].IsD()) { out.vertex_index[i] = nv++; out.source_vertex.push_back(int(i)); }
  for (size_t i = 0; i < src.face.size(); ++i)
    if (!src.face[i].IsD()) { out.face_index[i] = nf++; out.source_face.push_back(int(i)); }
  TriMesh& m = out.mesh;
  m.Clear();
  vcg::tri::Allocator<TriMesh>::AddVertices(m, nv);
  vcg::tri::Allocator<TriMesh>::AddFaces(m, nf);
  for (int j = 0; j < nv; ++j) {
    const auto& sv = src.vert[out.source_vertex[j]];
    m.vert[j].P() = Point3(sv.cP()[0], sv.cP()[1], sv.cP()[2]);
    if (sv.IsS()) m.vert[j].SetS();
  }
  for (int j = 0; j < nf; ++j) {
    const auto& sf = src.face[out.source_face[j]];
    for (int z = 0; z < 3; ++z) {
      int vi = out.vertex_index[vcg::tri::Index(src, sf.cV(z))];
      m.face[j].V(z) = &m.vert[vi];
      if (sf.IsFaceEdgeS(z)) m.face[j].SetFaceEdgeS(z);
      if (sf.IsF(z)) m.face[j].SetF(z);
    }
    if (sf.IsS()) m.face[j].SetS();
  }
  m.bbox.SetNull();
  for (const auto& v : m.vert) m.bbox.Add(v.cP());
}

/// Copies a core mesh into an empty CMeshO (positions, faces, faux edges, face-edge selection).
inline void copy_from_core(const TriMesh& src, CMeshO& dst) {
  dst.Clear();
  auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(dst, src.vert.size());
  (void)vi;
  vcg::tri::Allocator<CMeshO>::AddFaces(dst, src.face.size());
  for (size_t j = 0; j < src.vert.size(); ++j)
    dst.vert[j].P() = Point3m(src.vert[j].cP()[0], src.vert[j].cP()[1], src.vert[j].cP()[2]);
  for (size_t j = 0; j < src.face.size(); ++j)
    for (int z = 0; z < 3; ++z) {
      dst.face[j].V(z) = &dst.vert[vcg::tri::Index(src, src.face[j].cV(z))];
      if (src.face[j].IsF(z)) dst.face[j].SetF(z);
      if (src.face[j].IsFaceEdgeS(z)) dst.face[j].SetFaceEdgeS(z);
    }
  for (size_t j = 0; j < src.edge.size(); ++j) {
    auto e = vcg::tri::Allocator<CMeshO>::AddEdges(dst, 1);
    e->V(0) = &dst.vert[vcg::tri::Index(src, src.edge[j].cV(0))];
    e->V(1) = &dst.vert[vcg::tri::Index(src, src.edge[j].cV(1))];
  }
  vcg::tri::UpdateBounding<CMeshO>::Box(dst);
}

}  // namespace mr::bridge
