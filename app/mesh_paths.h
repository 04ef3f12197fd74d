// Mesh file names and size caps shared by the commands and the Python module.
#pragma once

#include <cstdint>
#include <string>

namespace intrinsic::app {

// Lower-case extension after stripping a trailing ".gz": "mesh.OBJ.gz" -> ".obj"
// ("" when there is none).
std::string mesh_extension(const std::string& path);

// The face cap that goes with a vertex cap: a manifold triangle mesh has about
// twice as many faces as vertices (4x leaves room for high genus and seams).
// It also bounds the gzip inflate cap, so --max-vertices limits memory.
std::int64_t faces_for_vertices(std::int64_t max_vertices);

}  // namespace intrinsic::app
