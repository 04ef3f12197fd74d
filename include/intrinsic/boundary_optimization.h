// Boundary optimization (paper section 5.2; docs/maths.md §8): move the
// boundary vertices (every loop, outer and holes) to minimise a distortion
// energy while the interior follows the chosen intrinsic map of that boundary.
//
// The interior is U_I = -A^{-1} K_IB U_B (A = K_II, factored once), so
// dE/dU_B = dE/dU_B|direct - K_IB^T A^{-T} dE/dU_I. Two routes give that:
//   adjoint:   one solve with A^T per gradient, whatever the boundary size;
//   responses: the paper's route, the boundary responses R = A^{-1} K_IB
//              precomputed once (n_free x n_boundary doubles), after which an
//              evaluation and a gradient are dense products, no solves.
// Descent is L-BFGS (or plain gradient descent to compare) with a
// backtracking line search that only accepts steps that lower the energy
// (Armijo), add no flipped triangle and make no boundary segments cross.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "intrinsic/choice.h"
#include "intrinsic/parameterizer.h"

namespace intrinsic {

enum class BoundaryEnergy { EdgeLength, Area, SymmetricDirichlet };
template <>
ChoiceTable<BoundaryEnergy> choice_table<BoundaryEnergy>();
enum class GradientRoute { Adjoint, Responses };
template <>
ChoiceTable<GradientRoute> choice_table<GradientRoute>();
enum class Descent { LBFGS, GradientDescent };
template <>
ChoiceTable<Descent> choice_table<Descent>();

BoundaryEnergy parse_boundary_energy(const std::string& name);  // edge | area | dirichlet
GradientRoute parse_gradient_route(const std::string& name);    // adjoint | responses
Descent parse_descent(const std::string& name);                 // lbfgs | gradient
std::string boundary_energy_name(BoundaryEnergy e);  // the names the parse functions take
std::string gradient_route_name(GradientRoute r);
std::string descent_name(Descent d);

struct BoundaryOptimizationOptions {
  ParamOptions base;  // weights of the interior map, starting boundary, holes rule for the start, solver
  BoundaryEnergy energy = BoundaryEnergy::EdgeLength;
  GradientRoute route = GradientRoute::Adjoint;
  Descent descent = Descent::LBFGS;
  int max_iterations = 200;
  double tolerance = 1e-6;  // stop when an iteration lowers the energy by less than this fraction
  int lbfgs_memory = 8;
  double responses_budget_bytes = 2.0 * (1u << 30);  // refuse the responses route above this
  std::function<void(int iteration, double energy)> progress;  // called after each iteration
};

struct BoundaryOptimizationResult {
  MatrixX2d UV;  // #V x 2, at the scale the energy chose (the surface's own scale)
  // The final map as a Parameterizer result (residual, free vertices, ...),
  // placed as base.scale says (Unit: fitted into [0,1]^2; Surface: as UV).
  ParamResult map;
  std::vector<double> energy_history;  // initial energy, then one per iteration
  int iterations = 0;
  int solves = 0;           // linear solves (each with 2 right-hand sides), responses excluded
  int response_solves = 0;  // right-hand sides solved to build the responses
  int factorizations = 0;   // the start map's and the objective's (1 when they share one)
  int flipped_initial = 0, flipped_final = 0;
  std::string stop_reason;
  double setup_ms = 0, optimize_ms = 0;
};

// Energy of a map and its gradient with respect to every UV (for tests and
// the optimizer). Symmetric Dirichlet is sum_f A_f (|J|^2 + |J^-1|^2), which
// is +inf on a flipped or collapsed triangle.
double boundary_energy(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, BoundaryEnergy e,
                       MatrixX2d* gradient);
// Same, with the edge list (unique_edges(F)) computed once by the caller.
double boundary_energy(const MatrixX3d& V, const MatrixX3i& F, const Eigen::MatrixX2i& edges, const MatrixX2d& UV,
                       BoundaryEnergy e, MatrixX2d* gradient);

BoundaryOptimizationResult optimize_boundary(const Mesh& mesh, const BoundaryOptimizationOptions& options);

// The objective as a function of the boundary positions x (u, v of each
// boundary vertex in turn, every loop): the map it induces and the energy
// with its gradient by the chosen route. It solves through a Parameterizer
// whose fixed vertices are all the loops (one factorization, kept);
// optimize_boundary uses it, and tool builders can drive their own descent
// with it.
class BoundaryObjective {
 public:
  // `start` (#V x 2) gives the first positions of the boundary. The options
  // are copied. Throws Error(Usage) when the responses would exceed their
  // memory budget.
  BoundaryObjective(const Mesh& mesh, const BoundaryOptimizationOptions& options, const MatrixX2d& start);
  // Takes over a Parameterizer whose fixed vertices are already every loop
  // vertex (no second factorization).
  BoundaryObjective(Parameterizer&& parameterizer, const BoundaryOptimizationOptions& options);
  ~BoundaryObjective();
  BoundaryObjective(BoundaryObjective&&) noexcept;

  int boundary_size() const;
  const std::vector<int>& boundary_vertices() const;
  const std::vector<std::array<int, 2>>& segments() const;
  Eigen::VectorXd boundary_of(const MatrixX2d& UV) const;
  MatrixX2d map(const Eigen::VectorXd& x);
  double energy(const MatrixX2d& UV, Eigen::VectorXd* gradient);
  // The Parameterizer's result for boundary x (one solve), placed by `scale`.
  ParamResult final_map(const Eigen::VectorXd& x, ScaleMode scale);

  int solves() const;           // linear solves so far (2 right-hand sides each), responses excluded
  int response_solves() const;  // right-hand sides solved to build the responses
  int factorizations() const;   // of the Parameterizer it solves with

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// True when two boundary segments that share no vertex cross in the plane.
bool boundary_crosses(const std::vector<std::array<int, 2>>& segments, const MatrixX2d& UV);

}  // namespace intrinsic
