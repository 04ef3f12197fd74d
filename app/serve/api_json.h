// The JSON bodies `intrinsic serve` answers with (README "intrinsic serve"):
// the mesh of GET /api/mesh and the map of POST /api/solve.
#pragma once

#include <string>

#include "intrinsic/mesh.h"
#include "serve/edit_session.h"

namespace intrinsic::app {

// {"vertices", "faces", "positions": [x0, y0, z0, ...], "triangles": [a0, b0, c0, ...],
//  "boundary_loops": [[...], ...]}
std::string mesh_api_json(const Mesh& mesh);
// {"uv": [[u, v], ...], "flipped_triangles", "angle_distortion_mean", "update_ms", "path"}
// plus "pins": [[vertex, u, v], ...] for the natural map.
std::string solve_api_json(const Mesh& mesh, const SolveAnswer& answer);
// {"error": message}
std::string error_api_json(const std::string& message);

}  // namespace intrinsic::app
