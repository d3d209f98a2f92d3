// The mesh type every MeshRegrid core works on: a VCGlib triangle mesh in double
// precision with the components the algorithms need always present (no optional
// components to enable), plus edges for polylines.
#pragma once

#include <vcg/complex/complex.h>

namespace mr {

class Vertex;
class Edge;
class Face;

struct UsedTypes : public vcg::UsedTypes<vcg::Use<Vertex>::AsVertexType,
                                         vcg::Use<Edge>::AsEdgeType,
                                         vcg::Use<Face>::AsFaceType> {};

class Vertex : public vcg::Vertex<UsedTypes, vcg::vertex::Coord3d, vcg::vertex::Normal3d,
                                  vcg::vertex::Qualityd, vcg::vertex::Color4b,
                                  vcg::vertex::VFAdj, vcg::vertex::Mark, vcg::vertex::BitFlags> {};

class Edge : public vcg::Edge<UsedTypes, vcg::edge::VertexRef, vcg::edge::BitFlags,
                              vcg::edge::EEAdj, vcg::edge::VEAdj> {};

class Face : public vcg::Face<UsedTypes, vcg::face::VertexRef, vcg::face::Normal3d,
                              vcg::face::Qualityd, vcg::face::Color4b, vcg::face::FFAdj,
                              vcg::face::VFAdj, vcg::face::Mark, vcg::face::BitFlags> {};

class TriMesh : public vcg::tri::TriMesh<std::vector<Vertex>, std::vector<Edge>, std::vector<Face>> {};

using Point3 = vcg::Point3d;
using Box3 = vcg::Box3d;

}  // namespace mr
