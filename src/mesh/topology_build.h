// Internal: the steps of building the adjacency, used by make_mesh.
#pragma once

#include <vector>

#include "intrinsic/mesh.h"

namespace intrinsic::detail {

// What orient_faces found that build_topology needs again: the outgoing
// half-edges of each vertex (compressed rows) and each half-edge's twin.
// Filled only when no face was flipped (flips renumber the half-edges).
struct OrientedAdjacency {
  std::vector<int> begin;      // size n+1
  std::vector<int> halfedges;  // 3m, grouped by source vertex
  std::vector<int> target;     // 3m, the target of each of halfedges
  std::vector<int> twin;       // 3m, -1 on the boundary; empty: not kept
};

// Flips faces so that every edge is traversed in opposite directions by its
// two faces, keeping the majority orientation of each component. Throws on
// non-manifold edges and non-orientable surfaces. Returns the number flipped;
// with `kept`, hands over the adjacency it built when nothing was flipped.
int orient_faces(Mesh& mesh, OrientedAdjacency* kept = nullptr);

// make_mesh (mesh.h), taking over data's V, F and face lines (left empty)
// instead of copying them: at 1M vertices they are 56 MB, whose copy (and
// first touch) was a fifth of validation. For the pipeline, which owns the
// file it read.
Mesh make_mesh_taking(MeshData&& data, const ValidateOptions& options = {});

// Fills mesh.topology (twins, vertex fans, loops, components) for a
// consistently oriented mesh; throws on non-manifold vertices. `known`
// (from orient_faces, moved from) spares rebuilding the outgoing lists and twins.
void build_topology(Mesh& mesh, OrientedAdjacency* known = nullptr);

}  // namespace intrinsic::detail
