// Bodies of `POST /api/optimal_lambda` and `POST /api/optimize_boundary`
// (docs/cli.md "intrinsic serve"; paper section 5.1 and 5.2, docs/maths.md §7, §8):
// a solve request (solve_request.h: method, boundary, moves; the session's
// fixed boundary after the moves is where they start) plus their own keys.
// Both refuse the natural boundary and constraints (the library's optimal
// lambda and boundary optimization take neither). Error(Usage) for anything
// malformed, as parse_solve_request.
#pragma once

#include <string>

#include "intrinsic/boundary_optimization.h"
#include "intrinsic/optimal_lambda.h"
#include "serve/solve_request.h"

namespace intrinsic::app {

struct OptimalLambdaRequest {
  SolveRequest solve;
  LambdaEnergy energy = LambdaEnergy::EdgeLength;  // "energy": "edge" | "area"
};

struct OptimizeBoundaryRequest {
  SolveRequest solve;                                // method, lambda, mu: the interior map's weights
  BoundaryEnergy energy = BoundaryEnergy::EdgeLength;  // "energy": "edge" | "area" | "dirichlet"
  int max_iterations = 100;                           // "max_iterations": 1..1000
};

OptimalLambdaRequest parse_optimal_lambda_request(const std::string& body, const Mesh& mesh,
                                                  const MatrixX3i& file_faces);
OptimizeBoundaryRequest parse_optimize_boundary_request(const std::string& body, const Mesh& mesh,
                                                        const MatrixX3i& file_faces);

}  // namespace intrinsic::app
