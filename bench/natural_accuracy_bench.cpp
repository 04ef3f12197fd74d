// natural_accuracy_bench: where the natural map's distance to its exact
// solution comes from
// (docs/performance.md#the-natural-map-a-complex-hermitian-factor).
// On one mesh:
//  (a) the pipeline's eliminated system (EliminatedSystem, as the
//      Parameterizer builds it) against the bench reference's (a triplet
//      build from assemble_natural_system, as intrinsic_bench's
//      natural_reference_uv), entry by entry;
//  (b) the complex factor's refinement, step by step, with the residual in
//      long double (the old rule) and in double-double (the library's now):
//      correction, componentwise backward error, error against (c);
//  (c) exact references: CHOLMOD on the real 2n system refined with a
//      double-double residual written here, against the same refined with a
//      long-double residual (the old reference's rule), and optionally
//      (--old) the old reference itself (Eigen's simplicial LL^T, slow).
//
//   natural_accuracy_bench MESH [--old | --complex-reference]
#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "compensated_residual.h"
#include "core/natural_system.h"
#include "intrinsic/io.h"
#include "intrinsic/parameterize.h"
#include "solve/complex_form.h"
#include "solve/eliminated_system.h"
#include "solve/suitesparse.h"
#include "solve/supernodal_cholesky.h"

using namespace intrinsic;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

Eigen::VectorXd residual_ld(const SparseMatrix& A, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  std::vector<long double> r(b.data(), b.data() + b.size());
  for (Eigen::Index j = 0; j < A.cols(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) r[it.row()] -= static_cast<long double>(it.value()) * x[j];
  Eigen::VectorXd out(b.size());
  for (Eigen::Index k = 0; k < b.size(); ++k) out[k] = static_cast<double>(r[k]);
  return out;
}

// The old library residual: long-double sums over M's lower triangle.
Eigen::VectorXcd complex_residual_ld(const detail::ComplexSparse& lower, const Eigen::VectorXcd& z,
                                     const Eigen::VectorXcd& b) {
  const Eigen::Index n = lower.rows();
  std::vector<long double> re(n), im(n);
  for (Eigen::Index i = 0; i < n; ++i) re[i] = b[i].real(), im[i] = b[i].imag();
  for (Eigen::Index j = 0; j < n; ++j) {
    const long double zr = z[j].real(), zi = z[j].imag();
    for (detail::ComplexSparse::InnerIterator it(lower, j); it; ++it) {
      const Eigen::Index i = it.row();
      const long double mr = -static_cast<long double>(it.value().real()), mi = -static_cast<long double>(it.value().imag());
      re[i] += mr * zr - mi * zi;
      im[i] += mr * zi + mi * zr;
      if (i != j) {
        const long double xr = z[i].real(), xi = z[i].imag();
        re[j] += mr * xr + mi * xi;
        im[j] += mr * xi - mi * xr;
      }
    }
  }
  Eigen::VectorXcd out(n);
  for (Eigen::Index i = 0; i < n; ++i) out[i] = {static_cast<double>(re[i]), static_cast<double>(im[i])};
  return out;
}

double rel(const Eigen::VectorXd& x, const Eigen::VectorXd& ref) {
  return (x - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
}

// Refines x with `solve` and `residual` for `steps` steps, printing each.
template <class Solve, class Residual>
Eigen::VectorXd refine(const char* label, Eigen::VectorXd x, int steps, Solve solve, Residual residual,
                       const Eigen::VectorXd* exact) {
  for (int step = 1; step <= steps; ++step) {
    const Eigen::VectorXd d = solve(residual(x));
    x += d;
    std::printf("  %-26s step %d: correction %.3e", label, step, d.cwiseAbs().maxCoeff() / x.cwiseAbs().maxCoeff());
    if (exact) std::printf("  error %.3e", rel(x, *exact));
    std::printf("\n");
  }
  return x;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) { std::fprintf(stderr, "usage: natural_accuracy_bench MESH [--old | --complex-reference]\n"); return 2; }
  const std::string flag = argc > 2 ? argv[2] : "";
  const bool old = flag == "--old", complex_reference = flag == "--complex-reference";
  const Mesh mesh = make_mesh(read_mesh(argv[1]));
  const int n = static_cast<int>(mesh.V.rows());
  ParamOptions o;
  o.boundary = BoundaryShape::Natural;
  o.scale = ScaleMode::Surface;
  const ParamResult pr = parameterize(mesh, o);
  std::printf("%s: %d vertices, pipeline solve %.3f s\n", argv[1], n, pr.timings.solve_ms / 1000);

  // (a) The pipeline's system, built as Parameterizer::Impl::build_natural does.
  std::vector<char> fixed2(2 * n, 0), used2(2 * n, 0);
  for (int v = 0; v < n; ++v) used2[v] = used2[n + v] = mesh.topology.is_used[v];
  for (const FixedVertex& p : pr.pins) fixed2[p.vertex] = fixed2[n + p.vertex] = 1;
  detail::EliminatedSystem::Factoring how;
  how.ill_conditioned = how.complex_form = true;
  Eigen::VectorXd b;
  SparseMatrix A;
  Partition part;
  {  // scoped: its factor is 1.3 GB at 1M vertices
    detail::EliminatedSystem sys(assemble_natural_system(mesh), fixed2, used2, how);
    part = sys.partition();
    Eigen::MatrixXd UB = Eigen::MatrixXd::Zero(sys.known_count(), 1);
    for (const FixedVertex& p : pr.pins) UB(part.fixed_index[p.vertex], 0) = p.uv.x(), UB(part.fixed_index[n + p.vertex], 0) = p.uv.y();
    b = sys.rhs(UB).col(0);
    A = sys.A();
  }

  // The bench reference's system (intrinsic_bench natural_reference_uv).
  const SparseMatrix Q = assemble_natural_system(mesh);
  std::vector<int> index(2 * n, -1), unknown;
  Eigen::VectorXd pinned = Eigen::VectorXd::Zero(2 * n);
  std::vector<char> is_pin(n, 0);
  for (const FixedVertex& p : pr.pins) is_pin[p.vertex] = 1, pinned[p.vertex] = p.uv.x(), pinned[n + p.vertex] = p.uv.y();
  int m = 0;
  for (int k = 0; k < 2 * n; ++k)
    if (mesh.topology.is_used[k % n] && !is_pin[k % n]) index[k] = m++, unknown.push_back(k);
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd b_ref = Eigen::VectorXd::Zero(m);
  for (int j = 0; j < 2 * n; ++j)
    for (SparseMatrix::InnerIterator it(Q, j); it; ++it) {
      if (index[it.row()] < 0) continue;
      if (index[j] >= 0) t.emplace_back(index[it.row()], index[j], it.value());
      else b_ref[index[it.row()]] -= it.value() * pinned[j];
    }
  SparseMatrix A_ref(m, m);
  A_ref.setFromTriplets(t.begin(), t.end());
  bool same_order = A.rows() == m;
  for (int r = 0; r < m && same_order; ++r) same_order = part.free_index[unknown[r]] == r;
  std::printf("(a) unknowns: pipeline %d, reference %d, same order %d\n", static_cast<int>(A.rows()), m, same_order);
  if (!same_order) return 1;
  const SparseMatrix diff = A - A_ref;
  double max_diff = 0;
  long differing = 0;
  for (Eigen::Index k = 0; k < diff.nonZeros(); ++k)
    if (diff.valuePtr()[k] != 0) ++differing, max_diff = std::max(max_diff, std::abs(diff.valuePtr()[k]));
  long b_differing = 0, b_nonzero = 0;
  for (int r = 0; r < m; ++r) b_differing += b[r] != b_ref[r], b_nonzero += b_ref[r] != 0;
  std::printf("    matrix: nnz pipeline %ld reference %ld, %ld entries differ (max |diff| %.3g)\n",
              static_cast<long>(A.nonZeros()), static_cast<long>(A_ref.nonZeros()), differing, max_diff);
  std::printf("    rhs: %ld nonzero, %ld differ\n", b_nonzero, b_differing);

  // (c) Exact references on the real 2n system.
  auto t0 = std::chrono::steady_clock::now();
  Eigen::VectorXd exact;
  {  // scoped: CHOLMOD's factor of the 2n system
  // CHOLMOD's real factor of the 2n system; with --complex-reference its
  // complex factor of the Hermitian form (the real one of the 1M system
  // needs more than 6 GB).
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> chol;
  detail::CholmodFactor zfactor;
  if (complex_reference) {
    if (!zfactor.factor(A_ref, detail::Structure::ComplexPairs)) return 1;
  } else {
    chol.cholmod().nmethods = 1;
    chol.cholmod().method[0].ordering = CHOLMOD_METIS;
    chol.compute(A_ref);
  }
  auto csolve = [&](const Eigen::VectorXd& r) {
    return complex_reference ? Eigen::VectorXd(zfactor.solve(r)) : Eigen::VectorXd(chol.solve(r));
  };
  const Eigen::VectorXd x0 = csolve(b_ref);
  std::printf("(c) CHOLMOD %s factor+solve %.1f s\n", complex_reference ? "complex" : "real 2n", seconds_since(t0));
  auto dd = [&](const Eigen::VectorXd& x) { return bench::compensated_residual(A_ref, x, b_ref); };
  auto ld = [&](const Eigen::VectorXd& x) { return residual_ld(A_ref, x, b_ref); };
  t0 = std::chrono::steady_clock::now();
  exact = refine("cholmod + double-double", x0, 6, csolve, dd, nullptr);
  std::printf("    (%.1f s)\n", seconds_since(t0));
  refine("cholmod + long double", x0, 6, csolve, ld, &exact);
  if (old) {
    t0 = std::chrono::steady_clock::now();
    Eigen::SimplicialLLT<SparseMatrix> llt(A_ref);
    auto esolve = [&](const Eigen::VectorXd& r) { return Eigen::VectorXd(llt.solve(r)); };
    refine("eigen llt + long double", llt.solve(b_ref), 6, esolve, ld, &exact);
    std::printf("    (%.1f s)\n", seconds_since(t0));
  }
  }

  // (b) The complex factor's refinement.
  detail::ComplexSparse M;
  if (!detail::hermitian_from_real_form(A, M)) { std::printf("not a real form\n"); return 1; }
  const detail::ComplexSparse lower(M.triangularView<Eigen::Lower>());
  {
  detail::ComplexSupernodalCholesky zchol;
  if (!zchol.factor(lower)) { std::printf("complex factor failed\n"); return 1; }
  const Eigen::Index h = m / 2;
  const Eigen::VectorXcd bz = detail::complex_from_real_form(b);
  auto zsolve = [&](const Eigen::VectorXd& r) {
    return Eigen::VectorXd(detail::real_form(zchol.solve(detail::complex_from_real_form(r))));
  };
  auto z_dd = [&](const Eigen::VectorXd& x) {
    double omega = 0;
    const Eigen::MatrixXcd R = detail::hermitian_lower_residual(lower, detail::complex_from_real_form(x), bz, &omega);
    std::printf("  [backward error %.3e]", omega);
    return Eigen::VectorXd(detail::real_form(R));
  };
  auto z_ld = [&](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(detail::real_form(complex_residual_ld(lower, detail::complex_from_real_form(x).col(0), bz)));
  };
  (void)h;
  const Eigen::VectorXd y0 = zsolve(b);
  std::printf("(b) complex factor, first solve: error %.3e\n", rel(y0, exact));
  refine("complex + long double", y0, 6, zsolve, z_ld, &exact);
  refine("complex + double-double", y0, 6, zsolve, z_dd, &exact);
  }

  // The library's solver as the pipeline runs it: steps and error.
  LinearSolver solver(SolverKind::Auto, true);
  solver.set_ill_conditioned(true);
  solver.set_complex_form(true);
  solver.factor(A);
  for (int run = 0; run < 3; ++run) {
    t0 = std::chrono::steady_clock::now();
    const Eigen::VectorXd x = solver.solve(b).col(0);
    std::printf("LinearSolver::solve: %.3f s, %d refinement steps, error %.3e\n", seconds_since(t0),
                solver.refinement_steps(), rel(x, exact));
  }

  // The pipeline's map itself against the exact solution.
  Eigen::VectorXd x_pipe(m);
  for (int r = 0; r < m; ++r) x_pipe[r] = pr.UV(unknown[r] % n, unknown[r] / n);
  std::printf("pipeline map vs exact: %.3e\n", rel(x_pipe, exact));
  return 0;
}
