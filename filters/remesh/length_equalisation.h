// Edge lengths after the front: where fronts meet, and around corners and short lines that
// must stay, the front leaves edges shorter than 0.7 or longer than 1.4 x the local size
// (armadillo at 1% with 30-degree ridges and min_line_length = target: 9.5% of the edges). Three
// moves bring them back, each only when its faces stay above min(their old smallest angle,
// `floor`):
// - a free point slides, on the input surface, towards where its edges have the local size;
// - a free point at the short end of an edge collapses onto the other end;
// - a long edge is split at its middle.
#pragma once

#include "remesh/mesh_measures.h"
#include "remesh/output_mesh.h"
#include "remesh/size_field.h"
#include "remesh/surface_locator.h"

#include <cstdint>
#include <unordered_set>
#include <vector>

namespace mr::remesh {

/// Moves free points of `movable` with an edge out of range to where fewer of their edges are
/// out of range (or, as many, nearer to the size), projected onto the input. Returns the moves.
int relax_edge_lengths(OutputMesh& out, const SurfaceLocator& locator, const SizeField& size,
                       const std::vector<char>& movable, double floor);

/// Removes free points of `movable` that end an edge shorter than kShortEdge x the local size by
/// moving them onto the other end, when no face folds, the removed point stays within a small
/// part of the size from the new faces (the output stays on the input surface), and no edge
/// becomes too long. Faces of `fixed` edges (undirected OutputMesh::edge_key) keep them: a
/// collapse never removes a feature edge. Removed points stay in `out.points`, used by no face.
int collapse_short_edges(OutputMesh& out, const std::unordered_set<std::uint64_t>& fixed,
                         const SurfaceLocator& locator, const SizeField& size, const std::vector<char>& movable,
                         double floor);

/// Splits edges longer than kLongEdge x the local size, one end in `movable`, at their middle
/// projected onto the input, when the four new faces stay above min(the two old faces' smallest
/// angle, `floor`), do not fold and have every edge in range. New points are free and movable
/// (appended to `movable`).
int split_long_edges(OutputMesh& out, const std::unordered_set<std::uint64_t>& fixed, const SurfaceLocator& locator,
                     const SizeField& size, std::vector<char>& movable, double floor);

}  // namespace mr::remesh
