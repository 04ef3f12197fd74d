// The JSON bodies `intrinsic serve` answers with (docs/cli.md "intrinsic serve"):
// the mesh of GET /api/mesh and the map of POST /api/solve.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "intrinsic/mesh.h"
#include "intrinsic/metrics.h"
#include "serve/solve_request.h"

namespace intrinsic::app {

// {"vertices", "faces", "positions": [x0, y0, z0, ...], "triangles": [a0, b0, c0, ...],
//  "boundary_loops": [[...], ...]} plus "file_triangles": {"f": [a, b, c], ...}
// for faces whose corners the file lists in another order (constraint
// barycentrics refer to the file's order).
std::string mesh_api_json(const Mesh& mesh, const MatrixX3i& file_faces);
// {"uv": [[u, v], ...], "flipped_triangles", "angle_distortion_mean",
//  "area_distortion_mean", "update_ms", "path", "factorizations"} plus
// "pins": [[vertex, u, v], ...] for the natural map, plus the keys of `extra`.
// `frames`: face_frames(mesh.V, mesh.F), computed once per server.
std::string solve_api_json(const Mesh& mesh, const FaceFrames& frames, const SolveAnswer& answer,
                           const nlohmann::json& extra = nlohmann::json::object());
// The same answer split for `POST /api/solve?uv=binary`: the JSON without
// "uv" (sent in the X-Answer header) and the UVs as little-endian float64
// u0 v0 u1 v1 ... (the body): no number printing or parsing on either side.
// `flips_only` (the float32 answers while dragging): "flipped_triangles"
// without the distortion means, whose singular values cost ten times the
// update at 100k vertices; the exact answer on release carries them.
std::string solve_api_header(const Mesh& mesh, const FaceFrames& frames, const SolveAnswer& answer,
                             bool flips_only = false);
// `float32`: the same values rounded to little-endian float32, half the bytes
// (`?uv=float32`, what the page asks for while a drag is under way).
std::string uv_binary(const MatrixX2d& uv, bool float32 = false);
// {"error": message}
std::string error_api_json(const std::string& message);

}  // namespace intrinsic::app
