// The body of `POST /api/solve` (docs/cli.md "intrinsic serve"): every key
// optional, unknown keys and wrong types refused. Every request body goes
// through parse_solve_request, which throws Error(Usage) for malformed JSON,
// unknown keys, wrong types, non-finite numbers and vertices out of range,
// and Error(Input) for a bad constraint object (the constraint file's parser).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "intrinsic/edit_session.h"
#include "intrinsic/mesh.h"

namespace intrinsic::app {

// The library's session request and answer (intrinsic/edit_session.h), as
// the server names them.
using SolveRequest = EditRequest;
using SolveAnswer = EditAnswer;
using EditSession = intrinsic::EditSession;

// `file_faces` are the faces as the mesh file lists them (constraint
// barycentrics refer to their corners).
SolveRequest parse_solve_request(const std::string& body, const Mesh& mesh, const MatrixX3i& file_faces);

// The two steps of parse_solve_request, for the other endpoints whose bodies
// are a solve request plus their own keys (optimize_request.h): the body as a
// JSON object (nesting checked first), then the solve keys read from it with
// `extra_keys` also allowed (and left to the caller).
nlohmann::json parse_request_body(const std::string& body);
SolveRequest solve_request_from(const nlohmann::json& body, const Mesh& mesh, const MatrixX3i& file_faces,
                                const std::vector<std::string>& extra_keys);

}  // namespace intrinsic::app
