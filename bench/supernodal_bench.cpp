// supernodal_bench: the numeric factorization and the two-column solve of
// the conformal system (circle boundary eliminated) of a generated wavy
// disk by CHOLMOD and by the library's supernodal Cholesky with 1 and with
// the machine's threads, and of the authalic system by the supernodal LU
// (1 thread and the machine's);
// the variants alternate within each round (the machine is shared), and each
// row is the median of the rounds. Same analysis for all (CHOLMOD's on the
// level-set nested dissection), so the flops are the same: the kernel
// (CHOLMOD vs ours on 1 thread) and the parallelism (ours, 1 vs N threads)
// separate. The last column is the largest relative residual
// |A X - B| / |B| of the unrefined solves, then how many refinement steps
// LinearSolver's rule (componentwise backward error above 16 ulps) would
// add, each one more solve. A line before the table gives
// the LU's flops in the top supernodes and those of them that run on one
// thread whatever the thread count (machine-independent: the bound on what
// a second core can give), and one the solve stage of the authalic map as
// the pipeline runs it: LinearSolver's refined solve of the right-hand side
// of the circle boundary (its refinement steps, which random right-hand
// sides do not show, and their cost).
//   supernodal_bench [VERTICES] [ROUNDS]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "weights/assemble.h"
#include "intrinsic/boundary.h"
#include "intrinsic/generate.h"
#include "solve/linear_solver.h"
#include "intrinsic/mesh.h"
#include "intrinsic/weights.h"

#if defined(INTRINSIC_HAVE_SUITESPARSE) && defined(INTRINSIC_HAVE_OPENBLAS)
#include "solve/suitesparse.h"
#include "solve/supernodal_cholesky.h"
#include "solve/supernodal_lu.h"
#include "solve/supernodal_schedule.h"
#endif

using namespace intrinsic;

namespace {

using intrinsic::bench::median;
using intrinsic::bench::ms_since;

// The interior system of the method with the outer loop fixed on the
// circle (arc-length spacing, as `intrinsic param`); boundary_rhs, if
// given, gets its right-hand side (u and v).
SparseMatrix interior_system(const Mesh& mesh, Method method, Eigen::MatrixXd* boundary_rhs = nullptr) {
  WeightOptions w;
  w.method = method;
  const SparseMatrix K = assemble_weight_matrix(mesh.V, mesh.F, w);
  const std::vector<int>& loop = mesh.topology.boundary_loops[0];
  std::vector<char> fixed(mesh.V.rows(), 0);
  for (int v : loop) fixed[v] = 1;
  const Partition p = partition(static_cast<int>(mesh.V.rows()), fixed, mesh.topology.is_used);
  SparseMatrix A, B;
  split_matrix(K, p, A, B);
  A.makeCompressed();
  if (boundary_rhs) {
    Eigen::MatrixXd all = Eigen::MatrixXd::Zero(mesh.V.rows(), 2);
    for (const FixedVertex& f : circle_boundary(mesh.V, loop, Spacing::ArcLength)) all.row(f.vertex) = f.uv.transpose();
    Eigen::MatrixXd UB(B.cols(), 2);
    for (int k = 0; k < B.cols(); ++k) UB.row(k) = all.row(p.fixed_vertices[k]);
    *boundary_rhs = -(B * UB);
  }
  return A;
}

// Componentwise backward error max_i |B - A X|_i / (|A| |X| + |B|)_i, the
// measure LinearSolver refines on (linear_solver.cpp), with R = B - A X.
double backward_error(const SparseMatrix& A, const Eigen::MatrixXd& X, const Eigen::MatrixXd& B, Eigen::MatrixXd& R) {
  R = B - A * X;
  Eigen::MatrixXd scale = B.cwiseAbs() + A.cwiseAbs() * X.cwiseAbs();
  double omega = 0;
  for (Eigen::Index k = 0; k < R.size(); ++k)
    if (scale.data()[k] > 0) omega = std::max(omega, std::abs(R.data()[k]) / scale.data()[k]);
  return omega;
}

// How many refinement steps LinearSolver would take after the first solve
// (it refines while the backward error is above 16 ulps, at most 3 for the
// LU, 5 for the Cholesky): each costs one more solve.
template <class Factor>
int refinement_steps(const Factor& f, const SparseMatrix& A, const Eigen::MatrixXd& B, int limit) {
  Eigen::MatrixXd X = f.solve(B), R;
  int steps = 0;
  for (double omega = backward_error(A, X, B, R);
       steps < limit && omega > 16 * std::numeric_limits<double>::epsilon(); omega = backward_error(A, X, B, R)) {
    X += f.solve(R);
    ++steps;
  }
  return steps;
}

struct Row {
  std::vector<double> analyse, factor, solve;
  double flops = 0, nnz = 0, residual = 0;
  int steps = -1;
};

}  // namespace

int main(int argc, char** argv) {
#if defined(INTRINSIC_HAVE_SUITESPARSE) && defined(INTRINSIC_HAVE_OPENBLAS)
  const int n = argc > 1 ? std::stoi(argv[1]) : 1000000;
  const int rounds = argc > 2 ? std::stoi(argv[2]) : 3;
  GenerateOptions g;
  g.rings = std::max(2, static_cast<int>(std::lround(std::sqrt(n / 3.0))));
  const Mesh mesh = make_mesh(generate_wavy_patch(g));
  const SparseMatrix C = interior_system(mesh, Method::Conformal);
  Eigen::MatrixXd boundary_rhs;
  const SparseMatrix U = interior_system(mesh, Method::Authalic, &boundary_rhs);
  const Eigen::MatrixXd rhs = Eigen::MatrixXd::Random(C.rows(), 2);
  const int threads = detail::hardware_threads();
  std::map<std::string, Row> rows;
  std::vector<double> refined_solve;
  double refined_residual = 0;
  auto time = [&](const std::string& name, auto&& f, const SparseMatrix& A) {
    Row& r = rows[name];
    if (!f.factor(A)) { std::cerr << name << ": factor failed\n"; return; }
    r.analyse.push_back(f.analyse_ms);
    r.factor.push_back(f.factor_ms);
    const auto t = std::chrono::steady_clock::now();
    const Eigen::MatrixXd X = f.solve(rhs);
    r.solve.push_back(ms_since(t));
    r.residual = std::max(r.residual, (A * X - rhs).norm() / rhs.norm());
    if (r.steps < 0) r.steps = refinement_steps(f, A, rhs, 5);
    r.flops = f.flops();
    r.nnz = f.factor_nonzeros();
  };
  for (int round = 0; round < rounds; ++round) {
    { detail::CholmodFactor f; time("conformal CHOLMOD", f, C); }
    { detail::SupernodalCholesky f(1); time("conformal ours, 1 thread", f, C); }
    { detail::SupernodalCholesky f(threads); time("conformal ours, " + std::to_string(threads) + " threads", f, C); }
    { detail::SupernodalLU f(1); time("authalic supernodal LU, 1 thread", f, U); }
    { detail::SupernodalLU f(threads); time("authalic supernodal LU, " + std::to_string(threads) + " threads", f, U); }
    {  // the solve stage of `intrinsic param --method authalic`: refined, on the circle's right-hand side
      LinearSolver solver(SolverKind::Auto, false);
      solver.factor(U);
      const auto t = std::chrono::steady_clock::now();
      const Eigen::MatrixXd X = solver.solve(boundary_rhs);
      refined_solve.push_back(ms_since(t));
      refined_residual = (U * X - boundary_rhs).norm() / boundary_rhs.norm();
    }
  }
  std::printf("n = %d unknowns (%d vertices), %d rounds, medians\n\n", static_cast<int>(C.rows()),
              static_cast<int>(mesh.V.rows()), rounds);
  {
    detail::SupernodalLU f(threads);
    if (f.factor(U))
      std::printf("supernodal LU: %.2f of %.2f GFlop in the top supernodes (after the subtrees), %.2f GFlop of those on "
                  "one thread whatever the thread count; %d top supernodes split between threads\n\n",
                  f.top_flops() / 1e9, f.flops() / 1e9, f.serial_flops() / 1e9, f.split_supernodes());
    if (f.factor_nonzeros() > 0)
      std::printf("authalic LinearSolver solve on the circle's right-hand side (2 columns, refined; %d refinement "
                  "steps, each one more LU solve and backward error): %.3f s, relative residual %.1e\n\n",
                  refinement_steps(f, U, boundary_rhs, 3), median(refined_solve) / 1000, refined_residual);
  }
  std::printf("| system / factorization | ordering + analysis s | numeric factor s | GFlop | GFlop/s | solve (2 rhs) s | nnz(factor) | max residual | refinement steps |\n|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& [name, r] : rows) {
    const double f = median(r.factor);
    std::printf("| %s | %.3f | %.3f | %.2f | %.2f | %.3f | %.0f | %.1e | %d |\n", name.c_str(), median(r.analyse) / 1000,
                f / 1000, r.flops / 1e9, r.flops / 1e6 / f, median(r.solve) / 1000, r.nnz, r.residual, r.steps);
  }
  return 0;
#else
  (void)argc;
  (void)argv;
  std::cerr << "built without SuiteSparse and OpenBLAS\n";
  return 2;
#endif
}
