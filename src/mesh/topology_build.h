// Internal: the steps of building the adjacency, used by make_mesh.
#pragma once

#include "intrinsic/mesh.h"

namespace intrinsic::detail {

// Flips faces so that every edge is traversed in opposite directions by its
// two faces, keeping the majority orientation of each component. Throws on
// non-manifold edges and non-orientable surfaces. Returns the number flipped.
int orient_faces(Mesh& mesh);

// Fills mesh.topology (twins, vertex fans, loops, components) for a
// consistently oriented mesh; throws on non-manifold vertices.
void build_topology(Mesh& mesh);

}  // namespace intrinsic::detail
