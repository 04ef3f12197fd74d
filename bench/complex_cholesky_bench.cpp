// complex_cholesky_bench: the natural map's complex Hermitian system (two
// boundary vertices pinned, complex form of docs/maths.md §3.6) of a
// generated wavy disk, factored and solved by CHOLMOD's complex supernodal
// factor and by the library's complex supernodal Cholesky (1 thread and the
// machine's threads). The variants alternate within each round (the machine
// is shared); each row is the median of the rounds. Same analysis (CHOLMOD's
// on the level-set nested dissection of the n-vertex graph), so the same
// flops: the rows separate the kernels and the parallelism. CHOLMOD's
// analysis time includes building M from the real form; ours is given M.
// The solve is one complex right-hand side, without refinement.
//   complex_cholesky_bench [VERTICES] [ROUNDS]
// With --relax first: our complex factor (the machine's threads) under
// several supernode amalgamations (suitesparse.h: SupernodeRelaxation),
// alternating within each round: nnz(L), flops, analysis and numeric time,
// and one unrefined 2-column solve.
//   complex_cholesky_bench --relax [VERTICES] [ROUNDS]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "core/natural_system.h"
#include "weights/assemble.h"
#include "intrinsic/generate.h"
#include "intrinsic/mesh.h"

#if defined(INTRINSIC_HAVE_SUITESPARSE) && defined(INTRINSIC_HAVE_OPENBLAS)
#include "solve/complex_form.h"
#include "solve/suitesparse.h"
#include "solve/supernodal_cholesky.h"
#include "solve/supernodal_schedule.h"
#endif

using namespace intrinsic;

namespace {

using intrinsic::bench::median;
using intrinsic::bench::ms_since;

struct Row {
  std::vector<double> analyse, factor, solve;
  double flops = 0, nnz = 0;
};

#if defined(INTRINSIC_HAVE_SUITESPARSE) && defined(INTRINSIC_HAVE_OPENBLAS)
// The amalgamations compared by --relax: CHOLMOD's default first, then
// tighter ones (fewer columns merged, fewer explicit zeros allowed).
struct NamedRelaxation {
  const char* name;
  detail::SupernodeRelaxation relax;
};
const NamedRelaxation kRelaxations[] = {
    {"cholmod 4,16,48 / 0.8,0.1,0.05", {{4, 16, 48}, {0.8, 0.1, 0.05}}},
    {"4,4,32 / 0.8,0.05,0.01", {{4, 4, 32}, {0.8, 0.05, 0.01}}},
    {"8,8,32 / 0.8,0.05,0.01", {{8, 8, 32}, {0.8, 0.05, 0.01}}},
    {"4,8,32 / 0.5,0.05,0.01", {{4, 8, 32}, {0.5, 0.05, 0.01}}},
    {"none 0,0,0 / 0,0,0", {{0, 0, 0}, {0, 0, 0}}},
};

int relax_sweep(const detail::ComplexSparse& M, int rounds) {
  const detail::ComplexSparse lower = M.triangularView<Eigen::Lower>();
  const Eigen::MatrixXcd rhs = Eigen::MatrixXcd::Random(M.rows(), 2);
  std::map<std::string, Row> rows;
  for (int round = 0; round < rounds; ++round)
    for (const NamedRelaxation& r : kRelaxations) {
      detail::ComplexSupernodalCholesky f;
      f.set_relaxation(r.relax);
      if (!f.factor(lower)) { std::cerr << "ours failed\n"; return 1; }
      Row& row = rows[r.name];
      row.analyse.push_back(f.analyse_ms);
      row.factor.push_back(f.factor_ms);
      const auto t = std::chrono::steady_clock::now();
      f.solve(rhs);
      row.solve.push_back(ms_since(t));
      row.flops = f.flops();
      row.nnz = f.factor_nonzeros();
    }
  std::printf("natural system: n = %d complex unknowns, %d rounds, medians, %d threads\n\n", static_cast<int>(M.rows()),
              rounds, detail::hardware_threads());
  std::printf("| nrelax / zrelax | analysis s | numeric s | GFlop (real) | GFlop/s | nnz(L) | L MB | solve (2 rhs) s |\n|---|---|---|---|---|---|---|---|\n");
  for (const NamedRelaxation& r : kRelaxations) {
    const Row& row = rows[r.name];
    const double f = median(row.factor);
    std::printf("| %s | %.3f | %.3f | %.2f | %.2f | %.0f | %.0f | %.3f |\n", r.name, median(row.analyse) / 1000, f / 1000,
                row.flops / 1e9, row.flops / 1e6 / f, row.nnz, row.nnz * 16 / 1e6, median(row.solve) / 1000);
  }
  return 0;
}
#endif

}  // namespace

int main(int argc, char** argv) {
#if defined(INTRINSIC_HAVE_SUITESPARSE) && defined(INTRINSIC_HAVE_OPENBLAS)
  const bool sweep = argc > 1 && std::string(argv[1]) == "--relax";
  if (sweep) {
    --argc;
    ++argv;
  }
  const int n = argc > 1 ? std::stoi(argv[1]) : 1000000;
  const int rounds = argc > 2 ? std::stoi(argv[2]) : 3;
  GenerateOptions g;
  g.rings = std::max(2, static_cast<int>(std::lround(std::sqrt(n / 3.0))));
  const Mesh mesh = make_mesh(generate_wavy_patch(g));
  const int nv = static_cast<int>(mesh.V.rows());
  const std::vector<int>& loop = mesh.topology.boundary_loops[0];
  std::vector<char> known(2 * nv, 0), used(2 * nv, 1);
  for (int v : {loop[0], loop[loop.size() / 2]}) known[v] = known[nv + v] = 1;
  const Partition p = partition(2 * nv, known, used);
  SparseMatrix A, A_IB;
  split_matrix(assemble_natural_system(mesh), p, A, A_IB);
  A.makeCompressed();
  detail::ComplexSparse M;
  if (!detail::hermitian_from_real_form(A, M)) { std::cerr << "not a real form\n"; return 1; }
  if (sweep) return relax_sweep(M, rounds);
  const Eigen::MatrixXd rhs = Eigen::MatrixXd::Random(A.rows(), 1);
  const Eigen::MatrixXcd rhs_z = detail::complex_from_real_form(rhs);
  const int threads = detail::hardware_threads();
  std::map<std::string, Row> rows;
  auto record = [&](const std::string& name, auto& f, double solve_ms) {
    Row& r = rows[name];
    r.analyse.push_back(f.analyse_ms);
    r.factor.push_back(f.factor_ms);
    r.solve.push_back(solve_ms);
    r.flops = f.flops();
    r.nnz = f.factor_nonzeros();
  };
  for (int round = 0; round < rounds; ++round) {
    {
      detail::CholmodFactor f;
      if (!f.factor(A, detail::Structure::ComplexPairs)) { std::cerr << "CHOLMOD failed\n"; return 1; }
      const auto t = std::chrono::steady_clock::now();
      f.solve(rhs);
      record("CHOLMOD complex (solve refines)", f, ms_since(t));
    }
    for (int th : {1, threads}) {
      detail::ComplexSupernodalCholesky f(th);
      if (!f.factor(M)) { std::cerr << "ours failed\n"; return 1; }
      const auto t = std::chrono::steady_clock::now();
      f.solve(rhs_z);
      record("ours complex, " + std::to_string(th) + " thread(s)", f, ms_since(t));
    }
  }
  std::printf("natural system: n = %d complex unknowns (%d vertices), %d rounds, medians\n\n",
              static_cast<int>(M.rows()), nv, rounds);
  std::printf("| factorization | ordering + analysis s | numeric factor s | GFlop (real) | GFlop/s | solve (1 rhs) s | nnz(L) |\n|---|---|---|---|---|---|---|\n");
  for (const auto& [name, r] : rows) {
    const double f = median(r.factor);
    std::printf("| %s | %.3f | %.3f | %.2f | %.2f | %.3f | %.0f |\n", name.c_str(), median(r.analyse) / 1000,
                f / 1000, r.flops / 1e9, r.flops / 1e6 / f, median(r.solve) / 1000, r.nnz);
  }
  return 0;
#else
  (void)argc;
  (void)argv;
  std::cerr << "built without SuiteSparse and OpenBLAS\n";
  return 2;
#endif
}
