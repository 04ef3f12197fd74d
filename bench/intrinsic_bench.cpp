// intrinsic_bench: end-to-end timings per stage and method on generated
// irregular curved disks of growing size and on a shared scanned mesh.
//
// Each (mesh, method) case runs in a child process (fork), so its peak
// memory (ru_maxrss, taken before the reference check) is its own. Per stage the median of --runs runs is
// reported; the scaling exponent is the least-squares slope of log(total)
// against log(V) over the generated meshes. Every case is checked against a
// plain reference solve (triplet assembly, Eigen's simplicial LDL^T or
// UMFPACK with its default analysis) to 1e-9 relative, the natural map
// against its exact solution (natural_reference_uv) to 1e-11, up to
// --check-max vertices.
//
//   intrinsic_bench [--sizes 10000,100000,300000,1000000] [--runs 3]
//                   [--methods conformal,authalic,mixed,natural] [--mesh FILE]...
//                   [--workdir DIR] [--check-max N] [--json FILE]
//   intrinsic_bench --orderings[-nd] N|FILE   (-nd: the library's ordering only)
//                   (conformal, authalic and natural systems of an
//                   N-vertex patch or a mesh file: analyse/factor time,
//                   fill and flops per ordering)
//   intrinsic_bench --orderings-analysis N|FILE
//                   (conformal system only: the library's ordering's CPU
//                   and wall time, CHOLMOD's supernodal analysis on it, and
//                   the fill and flops that analysis counts; no numeric
//                   factorization, so quick at 1M)
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cctype>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bench_timing.h"
#include "compensated_residual.h"
#include "weights/assemble.h"
#include "intrinsic/generate.h"
#include "intrinsic/io.h"
#include "intrinsic/metrics.h"
#include "intrinsic/parameterize.h"
#include "intrinsic/pipeline.h"
#include "core/natural_system.h"  // assemble_natural_system
#if __has_include("solve/suitesparse.h")  // absent when measuring older trees
#include "solve/suitesparse.h"
#include "solve/complex_form.h"
#include "solve/ordering.h"
#include "util/parallel_for.h"
#define INTRINSIC_BENCH_ORDERINGS 1
#endif
#ifdef INTRINSIC_HAVE_SUITESPARSE
#include <Eigen/UmfPackSupport>
#endif

using namespace intrinsic;
using Clock = std::chrono::steady_clock;

namespace {

using intrinsic::bench::median;
using intrinsic::bench::ms_since;

const char* kStages[] = {"read", "validate", "assemble", "factor", "solve", "write", "metrics", "total"};

struct CaseResult {
  std::string mesh;
  int vertices = 0;
  std::string method, solver;
  std::map<std::string, double> median_ms;
  double peak_mb = 0;
  double check_error = -1;  // max |uv - uv_ref| / max |uv_ref|; -1 = not checked
  double sensitivity = -1;  // natural map: how far rounding of the input moves the reference (same measure)
  bool ok = false;
  std::string error;
};

ParamOptions options_for(const std::string& method) {
  ParamOptions o;
  if (method == "natural") {
    o.boundary = BoundaryShape::Natural;  // conformal weights, two pins
    o.scale = ScaleMode::Surface;         // pins at their 3D distance, no fit (the reference is unscaled)
    return o;
  }
  o.weights.method = parse_method(method);
  if (method == "mixed") {
    o.weights.lambda = 0.5;
    o.weights.mu = 0.5;
  }
  return o;
}

// The natural map's reference: the 2n x 2n real system, assembled here by
// triplets, factored by CHOLMOD's complex supernodal LL^H of its Hermitian
// form (Eigen's simplicial LL^T without SuiteSparse) and refined with a residual
// of the real system
// exact to about twice double precision (compensated_residual.h) until the
// correction is at the level of an ulp of the solution: the exact solution of
// the system as assembled here, rounded to doubles, whatever its
// conditioning, and independent of the pipeline's complex factor and
// residual. (A long-double residual, used before, left this reference itself
// up to ~4e-13 from exact at 100k vertices:
// docs/performance.md#the-natural-map-a-complex-hermitian-factor.)
// With `perturb`, every matrix entry and right-hand side value is first
// multiplied by (1 + u eps), u uniform in [-1, 1]: the distance between the
// two references is how far the map moves under rounding of its own input,
// the accuracy any double-precision pipeline can be asked for.
MatrixX2d natural_reference_uv(const Mesh& mesh, const ParamResult& ours, bool perturb) {
  const SparseMatrix Q = assemble_natural_system(mesh);
  const int n = static_cast<int>(mesh.V.rows());
  std::vector<int> index(2 * n, -1);
  Eigen::VectorXd pinned = Eigen::VectorXd::Zero(2 * n);
  std::vector<char> is_pin(n, 0);
  for (const FixedVertex& p : ours.pins) is_pin[p.vertex] = 1, pinned[p.vertex] = p.uv.x(), pinned[n + p.vertex] = p.uv.y();
  int m = 0;
  for (int k = 0; k < 2 * n; ++k)
    if (mesh.topology.is_used[k % n] && !is_pin[k % n]) index[k] = m++;
  // The perturbation of an entry is a hash of its place in the complex
  // form, so that the perturbed matrix is still a real form [K -B; B K]
  // (the pipeline's input is that Hermitian form; and CHOLMOD factors it).
  const std::uint64_t h = static_cast<std::uint64_t>(m / 2);
  auto jitter = [&](double x, std::uint64_t key) {
    if (!perturb) return x;
    std::uint64_t z = key * 0x9E3779B97F4A7C15ull + 0xD1B54A32D192ED03ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    const double u = static_cast<double>(z >> 11) / 9007199254740992.0 * 2 - 1;
    return x * (1 + u * std::numeric_limits<double>::epsilon());
  };
  auto entry_key = [&](std::uint64_t r, std::uint64_t c) {
    const std::uint64_t i = r % h, j = c % h;
    return (std::min(i, j) * h + std::max(i, j)) * 2 + ((r < h) != (c < h));
  };
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
  for (int j = 0; j < 2 * n; ++j)
    for (SparseMatrix::InnerIterator it(Q, j); it; ++it) {
      const int r = index[it.row()], c = index[j];
      if (r < 0) continue;
      if (c >= 0) t.emplace_back(r, c, jitter(it.value(), entry_key(r, c)));
      else b[r] -= it.value() * pinned[j];
    }
  for (int k = 0; k < m; ++k) b[k] = jitter(b[k], 2 * h * h + k);
  SparseMatrix A(m, m);
  A.setFromTriplets(t.begin(), t.end());
#if defined(INTRINSIC_BENCH_ORDERINGS) && defined(INTRINSIC_HAVE_SUITESPARSE)
  // CHOLMOD's complex factor of the Hermitian form: its real 2n factor of
  // the 1M-vertex system does not fit in 6 GB. A is [K -B; B K] here.
  detail::CholmodFactor llt;
  if (!llt.factor(A, detail::Structure::ComplexPairs)) return MatrixX2d::Constant(n, 2, NAN);
  const auto solve = [&](const Eigen::VectorXd& r) { return Eigen::VectorXd(llt.solve(r)); };
#else
  Eigen::SimplicialLLT<SparseMatrix> llt(A);
  const auto solve = [&](const Eigen::VectorXd& r) { return Eigen::VectorXd(llt.solve(r)); };
#endif
  Eigen::VectorXd x = solve(b);
  double previous = std::numeric_limits<double>::infinity();
  for (int step = 0; step < 10; ++step) {
    const Eigen::VectorXd d = solve(intrinsic::bench::compensated_residual(A, x, b));
    x += d;
    const double correction = d.cwiseAbs().maxCoeff() / x.cwiseAbs().maxCoeff();
    if (!(correction > 2 * std::numeric_limits<double>::epsilon()) || !(correction < 0.5 * previous)) break;
    previous = correction;
  }
  MatrixX2d UV = MatrixX2d::Zero(n, 2);
  for (int k = 0; k < 2 * n; ++k) {
    const double value = index[k] >= 0 ? x[index[k]] : pinned[k];
    if (mesh.topology.is_used[k % n]) UV(k % n, k / n) = value;
  }
  return UV;
}

// The plain path the fast one must agree with: triplet assembly of the whole
// matrix, triplet split, and a solver with its own default analysis.
MatrixX2d reference_uv(const Mesh& mesh, const ParamOptions& o, const ParamResult& ours) {
  if (o.boundary == BoundaryShape::Natural) return natural_reference_uv(mesh, ours, false);
  const int n = static_cast<int>(mesh.V.rows());
  std::vector<Eigen::Triplet<double>> t;
  for (int f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Matrix3d W = face_weights(mesh.V, mesh.F, f, o.weights);
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d)
        if (c != d) {
          t.emplace_back(mesh.F(f, c), mesh.F(f, d), -W(c, d));
          t.emplace_back(mesh.F(f, c), mesh.F(f, c), W(c, d));
        }
  }
  SparseMatrix K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  const std::vector<int>& outer = mesh.topology.boundary_loops[mesh.topology.component_loops[0][0]];
  const std::vector<FixedVertex> fixed = circle_boundary(mesh.V, outer, o.spacing);
  std::vector<int> fixed_index(n, -1), free_index(n, -1);
  for (size_t k = 0; k < fixed.size(); ++k) fixed_index[fixed[k].vertex] = static_cast<int>(k);
  int nf = 0;
  for (int v = 0; v < n; ++v)
    if (fixed_index[v] < 0 && mesh.topology.is_used[v]) free_index[v] = nf++;
  std::vector<Eigen::Triplet<double>> ii;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nf, 2);
  for (int j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(K, j); it; ++it) {
      const int r = free_index[it.row()];
      if (r < 0) continue;
      if (free_index[j] >= 0) ii.emplace_back(r, free_index[j], it.value());
      else if (fixed_index[j] >= 0) rhs.row(r) -= it.value() * fixed[fixed_index[j]].uv.transpose();
    }
  SparseMatrix A(nf, nf);
  A.setFromTriplets(ii.begin(), ii.end());
  Eigen::MatrixXd X;
  if (is_symmetric(o.weights)) {
    Eigen::SimplicialLDLT<SparseMatrix> s(A);
    X = s.solve(rhs);
  } else {
#ifdef INTRINSIC_HAVE_SUITESPARSE
    Eigen::UmfPackLU<SparseMatrix> s(A);
    X = s.solve(rhs);
#else
    Eigen::SparseLU<SparseMatrix> s(A);
    X = s.solve(rhs);
#endif
  }
  MatrixX2d UV = MatrixX2d::Zero(n, 2);
  for (int v = 0; v < n; ++v) {
    if (free_index[v] >= 0) UV.row(v) = X.row(free_index[v]);
    else if (fixed_index[v] >= 0) UV.row(v) = fixed[fixed_index[v]].uv.transpose();
  }
  for (int v = 0; v < n; ++v)
    if (mesh.topology.is_used[v]) UV.row(v) = 0.5 * UV.row(v) + Eigen::RowVector2d(0.5, 0.5);
  return UV;
}

// Runs one case (in the child): `runs` times read..metrics.
CaseResult run_case(const std::string& path, const std::string& method, int runs, const std::string& workdir,
                    int check_max) {
  CaseResult r;
  r.mesh = path;
  r.method = method;
  std::map<std::string, std::vector<double>> times;
  MatrixX2d UV;
  Mesh mesh;
  ParamResult last;
  // What `intrinsic param` runs: the library's pipeline, which reads,
  // validates, solves, then writes the OBJ while it measures the map; its
  // own stage timings fill the columns (write and metrics overlap, so the
  // total is less than the sum of the columns).
  ParamRequest request;
  request.options = options_for(method);
  request.output = workdir + "/bench-out.obj";
  for (int run = 0; run < runs; ++run) {
    mesh = Mesh();  // the last run's mesh is not part of this run's memory
    const auto t0 = Clock::now();
    ParamOutcome o = parameterize_file(path, request);
    times["total"].push_back(ms_since(t0));
    times["read"].push_back(o.read_ms);
    times["validate"].push_back(o.validate_ms);
    times["assemble"].push_back(o.map.timings.assemble_ms);
    times["factor"].push_back(o.map.timings.factor_ms);
    times["solve"].push_back(o.map.timings.solve_ms);
    times["write"].push_back(o.write_ms);
    times["metrics"].push_back(o.metrics_ms);
    r.solver = solvers_name(o.map.solvers);
    UV = o.map.UV;
    last = std::move(o.map);
    mesh = std::move(o.mesh);
  }
  r.vertices = static_cast<int>(mesh.V.rows());
  for (auto& [stage, x] : times) r.median_ms[stage] = median(x);
  struct rusage ru {};
  getrusage(RUSAGE_SELF, &ru);  // before the reference solve, which is not part of the pipeline
  r.peak_mb = ru.ru_maxrss / 1024.0;
  if (r.vertices <= check_max) {
    const MatrixX2d ref = reference_uv(mesh, options_for(method), last);
    r.check_error = (UV - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
    if (method == "natural") {
      const MatrixX2d moved = natural_reference_uv(mesh, last, true);
      r.sensitivity = (moved - ref).cwiseAbs().maxCoeff() / ref.cwiseAbs().maxCoeff();
    }
  }
  // The natural map is checked against its exact solution (goal 1e-11).
  r.ok = r.check_error <= (method == "natural" ? 1e-11 : 1e-9);
  return r;
}

std::string to_line(const CaseResult& r) {
  std::ostringstream s;
  s.precision(10);
  s << r.mesh << '\t' << r.vertices << '\t' << r.method << '\t' << r.solver << '\t' << r.check_error << '\t'
    << r.sensitivity << '\t' << r.ok << '\t' << r.peak_mb;
  for (const char* st : kStages) s << '\t' << r.median_ms.at(st);
  return s.str();
}

CaseResult from_line(const std::string& line) {
  std::istringstream s(line);
  CaseResult r;
  std::string field;
  std::getline(s, r.mesh, '\t');
  std::getline(s, field, '\t');
  r.vertices = std::stoi(field);
  std::getline(s, r.method, '\t');
  std::getline(s, r.solver, '\t');
  std::getline(s, field, '\t');
  r.check_error = std::stod(field);
  std::getline(s, field, '\t');
  r.sensitivity = std::stod(field);
  std::getline(s, field, '\t');
  r.ok = field == "1";
  std::getline(s, field, '\t');
  r.peak_mb = std::stod(field);
  for (const char* st : kStages) {
    std::getline(s, field, '\t');
    r.median_ms[st] = std::stod(field);
  }
  return r;
}

// Forks a child for the case; its stdout line comes back through a pipe.
CaseResult run_child(const std::string& path, const std::string& method, int runs, const std::string& workdir,
                     int check_max) {
  int fd[2];
  if (pipe(fd) != 0) throw std::runtime_error("pipe failed");
  std::cout.flush();
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    std::string line;
    try {
      line = to_line(run_case(path, method, runs, workdir, check_max));
    } catch (const std::exception& e) {
      line = std::string("ERROR\t") + e.what();
    }
    line += '\n';
    if (write(fd[1], line.data(), line.size()) < 0) _exit(2);
    close(fd[1]);
    _exit(0);
  }
  close(fd[1]);
  std::string line;
  char buf[4096];
  ssize_t got;
  while ((got = read(fd[0], buf, sizeof buf)) > 0) line.append(buf, static_cast<size_t>(got));
  close(fd[0]);
  int status = 0;
  struct rusage ru {};
  wait4(pid, &status, 0, &ru);
  CaseResult r;
  if (line.rfind("ERROR\t", 0) == 0 || line.empty()) {
    r.mesh = path;
    r.method = method;
    r.error = line.empty() ? "child died (status " + std::to_string(status) + ")" : line.substr(6);
    while (!r.error.empty() && r.error.back() == '\n') r.error.pop_back();
    r.peak_mb = ru.ru_maxrss / 1024.0;
    return r;
  }
  line.pop_back();
  return from_line(line);
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string fmt(double ms) {
  char b[32];
  std::snprintf(b, sizeof b, ms >= 100 ? "%.2f" : "%.3f", ms / 1000);
  return b;
}

#if defined(INTRINSIC_HAVE_SUITESPARSE) && defined(INTRINSIC_BENCH_ORDERINGS)
// --orderings-time: the library's ordering alone on the conformal and the
// complex natural pattern, no factorization (before/after timing runs).
bool g_order_time_only = false;

// The library's ordering alone on `pattern` (median of 3 runs, ms of this
// thread's CPU time: it runs on one thread, and CPU time is what other jobs
// on a shared machine disturb least), for the nested-dissection rows:
// CHOLMOD's analyse time adds its symbolic analysis.
double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}
double nd_order_ms(const SparseMatrix& pattern, detail::Ordering ord) {
  if (ord != detail::Ordering::NestedDissection) return -1;
  std::vector<double> t;
  for (int run = 0; run < 3; ++run) {
    const double t0 = thread_cpu_ms();
    const std::vector<int> p = detail::level_set_nested_dissection(pattern);
    t.push_back(thread_cpu_ms() - t0);
  }
  std::sort(t.begin(), t.end());
  return t[1];
}

// One table row: factor A with f, time one solve of two right-hand sides.
template <typename Factor>
void ordering_row(const std::string& system, Factor&& f, const SparseMatrix& A, detail::Ordering ord,
                  double order_ms) {
  const Eigen::MatrixXd rhs = Eigen::MatrixXd::Random(A.rows(), 2);
  const auto t = Clock::now();
  f.solve(rhs);
  const double solve = ms_since(t);
  std::cout << "| " << system << " | " << detail::ordering_name(ord) << " | "
            << (order_ms < 0 ? std::string("-") : fmt(order_ms)) << " | " << fmt(f.analyse_ms) << " | "
            << fmt(f.factor_ms) << " | " << fmt(solve) << " | " << static_cast<long>(f.factor_nonzeros()) << " | "
            << std::fixed << std::setprecision(2) << f.flops() / 1e9 << std::defaultfloat << " |" << std::endl;
}

// The conformal and authalic systems (circle boundary eliminated) and the
// natural map's (two pins), the latter factored in its real 2n x 2n form and
// in its complex Hermitian form (docs/maths.md §3.6).
void ordering_rows(const Mesh& mesh, detail::Ordering ord) {
  for (const char* method : {"conformal", "authalic"}) {
    if (g_order_time_only && std::string(method) == "authalic") continue;
    const ParamOptions o = options_for(method);
    const SparseMatrix K = assemble_weight_matrix(mesh.V, mesh.F, o.weights);
    std::vector<char> fixed(mesh.V.rows(), 0);
    for (int v : mesh.topology.boundary_loops[0]) fixed[v] = 1;
    const Partition p = partition(static_cast<int>(mesh.V.rows()), fixed, mesh.topology.is_used);
    SparseMatrix A, B;
    split_matrix(K, p, A, B);
    const std::string n = ", n = " + std::to_string(A.rows()) + ")";
    if (g_order_time_only) {
      std::cout << method << " order s " << fmt(nd_order_ms(A, ord)) << std::endl;
      continue;
    }
    if (is_symmetric(o.weights)) {
      detail::CholmodFactor f(ord);
      f.factor(A);
      ordering_row(std::string(method) + " (CHOLMOD" + n, f, A, ord, nd_order_ms(A, ord));
    } else {
      detail::UmfpackFactor f(ord);
      f.factor(A);
      ordering_row(std::string(method) + " (UMFPACK" + n, f, A, ord, nd_order_ms(A, ord));
    }
  }
  const int nv = static_cast<int>(mesh.V.rows());
  const auto [a, b] = default_pin_pair(mesh);
  std::vector<char> known(2 * nv, 0), used(2 * nv, 0);
  for (int v = 0; v < nv; ++v) used[v] = used[nv + v] = mesh.topology.is_used[v];
  for (int v : {a, b}) known[v] = known[nv + v] = 1;
  const Partition p = partition(2 * nv, known, used);
  SparseMatrix A, B;
  split_matrix(assemble_natural_system(mesh), p, A, B);
  if (g_order_time_only) {
    detail::ComplexSparse M;
    if (detail::hermitian_from_real_form(A, M))
      std::cout << "natural complex order s " << fmt(nd_order_ms(SparseMatrix(M.cwiseAbs()), ord)) << std::endl;
    return;
  }
  for (detail::Structure st : {detail::Structure::Real, detail::Structure::ComplexPairs}) {
    detail::CholmodFactor f(ord);
    f.factor(A, st);
    const std::string form = f.complex() ? "complex, n = " + std::to_string(A.rows() / 2)
                                         : "real, n = " + std::to_string(A.rows());
    detail::ComplexSparse M;
    const double order_ms = !f.complex()                           ? nd_order_ms(A, ord)
                            : detail::hermitian_from_real_form(A, M) ? nd_order_ms(SparseMatrix(M.cwiseAbs()), ord)
                                                                     : -1;
    ordering_row("natural (CHOLMOD " + form + ")", f, A, ord, order_ms);
  }
}
#endif

#if defined(INTRINSIC_HAVE_SUITESPARSE) && defined(INTRINSIC_BENCH_ORDERINGS)
double process_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

// --orderings-analysis: on the conformal system (circle boundary
// eliminated), the ordering's process CPU and wall time and CHOLMOD's
// analysis time on it (medians of `runs`), with the analysis's counts and
// a hash of the permutation (to see that a change kept it). The calling
// thread's CPU time bounds the ordering's wall time on idle cores from
// below (that thread cuts the whole graph first, the others join in, and
// it only waits when no piece is left for it), a figure the other jobs on a
// shared machine disturb much less than the wall time.
void analysis_row(const SparseMatrix& A, int runs, int threads) {
  detail::thread_limit() = threads;
  std::vector<double> cpu, own_cpu, wall, analyse, analyse_cpu;
  std::vector<int> order;
  detail::SupernodalSymbolic S;
  for (int run = 0; run < runs; ++run) {
    const double c0 = process_cpu_ms(), o0 = thread_cpu_ms();
    auto t = Clock::now();
    order = detail::level_set_nested_dissection(A);
    wall.push_back(ms_since(t));
    cpu.push_back(process_cpu_ms() - c0);
    own_cpu.push_back(thread_cpu_ms() - o0);
    const double a0 = process_cpu_ms();
    t = Clock::now();
    detail::supernodal_analysis(A, order, S);
    analyse.push_back(ms_since(t));
    analyse_cpu.push_back(process_cpu_ms() - a0);
  }
  detail::thread_limit() = 0;
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a of the permutation
  for (int v : order) hash = (hash ^ static_cast<std::uint64_t>(v)) * 1099511628211ull;
  std::cout << "| " << A.rows() << " | " << (threads > 0 ? std::to_string(threads) : std::string("all")) << " | "
            << fmt(median(cpu)) << " | " << fmt(median(own_cpu)) << " | " << fmt(median(wall)) << " | "
            << fmt(median(analyse_cpu)) << " | " << fmt(median(analyse)) << " | " << S.nsuper << " | "
            << static_cast<long>(S.nonzeros) << " | " << std::fixed << std::setprecision(3) << S.flops / 1e9
            << std::defaultfloat << " | " << std::hex << hash << std::dec << " |" << std::endl;
}

void analysis_rows(const Mesh& mesh, int runs) {
  const ParamOptions o = options_for("conformal");
  const SparseMatrix K = assemble_weight_matrix(mesh.V, mesh.F, o.weights);
  std::vector<char> fixed(mesh.V.rows(), 0);
  for (int v : mesh.topology.boundary_loops[0]) fixed[v] = 1;
  const Partition p = partition(static_cast<int>(mesh.V.rows()), fixed, mesh.topology.is_used);
  SparseMatrix A, B;
  split_matrix(K, p, A, B);
  A.makeCompressed();
  // One thread, then all cores, alternately (machine load shifts between
  // runs; the ordering must not depend on the thread count).
  for (int round = 0; round < 2; ++round)
    for (int threads : {1, 0}) analysis_row(A, runs, threads);
}
#endif

#if defined(INTRINSIC_HAVE_SUITESPARSE) && defined(INTRINSIC_BENCH_ORDERINGS)
// The ordering modes' mesh: a generated wavy patch of about N vertices when
// `what` is a number, else the mesh file it names.
Mesh size_or_file_mesh(const std::string& what) {
  if (what.empty() || !std::isdigit(static_cast<unsigned char>(what[0]))) return make_mesh(read_mesh(what));
  GenerateOptions g;
  g.rings = std::max(2, static_cast<int>(std::lround(std::sqrt(std::stoi(what) / 3.0))));
  return make_mesh(generate_wavy_patch(g));
}
#endif

int ordering_analysis(const std::string& what, int runs) {
#if defined(INTRINSIC_HAVE_SUITESPARSE) && defined(INTRINSIC_BENCH_ORDERINGS)
  const Mesh mesh = size_or_file_mesh(what);
  std::cout << "| n (conformal) | threads | order s (CPU) | order s (calling thread's CPU) | order s (wall) | "
               "analyse s (CPU) | analyse s (wall) | supernodes | nnz(L) | GFlop | permutation hash |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|\n";
  analysis_rows(mesh, runs);
  return 0;
#else
  (void)what;
  (void)runs;
  std::cerr << "--orderings-analysis needs SuiteSparse\n";
  return 1;
#endif
}

int orderings(const std::string& what, bool nested_dissection_only) {
#if defined(INTRINSIC_HAVE_SUITESPARSE) && defined(INTRINSIC_BENCH_ORDERINGS)
  const Mesh mesh = size_or_file_mesh(what);
  std::cout << "| system | ordering | order s (CPU) | analyse s | factor s | solve s | nnz(factor) | GFlop |\n"
               "|---|---|---|---|---|---|---|---|\n";
  for (detail::Ordering ord : {detail::Ordering::NestedDissection, detail::Ordering::AMD, detail::Ordering::METIS})
    if (!nested_dissection_only || ord == detail::Ordering::NestedDissection) ordering_rows(mesh, ord);
  return 0;
#else
  (void)what;
  (void)nested_dissection_only;
  std::cerr << "--orderings needs SuiteSparse\n";
  return 1;
#endif
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes = {10000, 100000, 300000, 1000000};
  std::vector<std::string> methods = {"conformal", "authalic", "mixed", "natural"};
  std::vector<std::string> meshes;
  std::string workdir = "/tmp", json;
  int runs = 3, check_max = 1100000;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--sizes") {
      sizes.clear();
      for (const std::string& s : split(next())) sizes.push_back(std::stoi(s));
    } else if (a == "--runs") runs = std::stoi(next());
    else if (a == "--methods") methods = split(next());
    else if (a == "--mesh") meshes.push_back(next());
    else if (a == "--workdir") workdir = next();
    else if (a == "--check-max") check_max = std::stoi(next());
    else if (a == "--orderings") return orderings(next(), false);
    else if (a == "--orderings-nd") return orderings(next(), true);
    else if (a == "--orderings-analysis") return ordering_analysis(next(), runs);
    else if (a == "--orderings-time") {  // the library's ordering's time only
      g_order_time_only = true;
      return orderings(next(), true);
    }  // the library's ordering only (fast at 1M)
    else {
      std::cerr << "usage: intrinsic_bench [--sizes N,N,...] [--runs R] [--methods m,...] [--mesh FILE]... "
                   "[--workdir DIR] [--check-max N] | --orderings N|FILE | --orderings-nd N|FILE\n"
                   "       intrinsic_bench [--runs R] --orderings-analysis N|FILE\n";
      return 2;
    }
  }
  // Generated meshes are written once (in a child, to keep this process
  // small) so the read stage parses a real file.
  std::vector<std::string> inputs;
  for (int n : sizes) {
    const std::string path = workdir + "/bench-wave-" + std::to_string(n) + ".obj";
    if (access(path.c_str(), R_OK) != 0) {
      const pid_t pid = fork();
      if (pid == 0) {
        GenerateOptions g;
        g.rings = std::max(2, static_cast<int>(std::lround(std::sqrt(n / 3.0))));
        const MeshData m = generate_wavy_patch(g);
        write_mesh(path, m.V, m.F, MatrixX2d());
        _exit(0);
      }
      int status = 0;
      waitpid(pid, &status, 0);
    }
    inputs.push_back(path);
  }
  const size_t generated = inputs.size();
  inputs.insert(inputs.end(), meshes.begin(), meshes.end());

  std::cout << "| mesh | V | method | solver | read | validate | assemble | factor | solve | write | metrics | total s | peak MB | max rel. diff |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::map<std::string, std::vector<std::pair<double, double>>> fit;  // method -> (V, total)
  for (size_t k = 0; k < inputs.size(); ++k)
    for (const std::string& method : methods) {
      const CaseResult r = run_child(inputs[k], method, runs, workdir, check_max);
      std::string name = inputs[k].substr(inputs[k].find_last_of('/') + 1);
      if (!r.error.empty()) {
        std::cout << "| " << name << " | | " << method << " | failed: " << r.error << " | | | | | | | | | "
                  << static_cast<long>(r.peak_mb) << " | |" << std::endl;
        continue;
      }
      std::cout << "| " << name << " | " << r.vertices << " | " << method << " | " << r.solver;
      for (const char* st : kStages) std::cout << " | " << fmt(r.median_ms.at(st));
      char err[32];
      std::snprintf(err, sizeof err, "%.1e", r.check_error);
      std::string verdict = r.ok ? "" : " FAIL";
      if (!r.ok && r.sensitivity >= 0 && r.check_error <= 10 * r.sensitivity) verdict = " (within rounding sensitivity)";
      if (r.sensitivity >= 0) {
        char sens[48];
        std::snprintf(sens, sizeof sens, "; sensitivity %.1e", r.sensitivity);
        verdict += sens;
      }
      std::cout << " | " << static_cast<long>(r.peak_mb) << " | "
                << (r.check_error < 0 ? "not checked" : std::string(err) + verdict) << " |" << std::endl;
      if (k < generated) fit[method].emplace_back(r.vertices, r.median_ms.at("total"));
    }
  std::cout << "\nScaling exponent (least-squares slope of log total time against log V, generated meshes):";
  for (const auto& [method, pts] : fit) {
    if (pts.size() < 2) continue;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (auto [v, t] : pts) {
      const double x = std::log(v), y = std::log(t);
      sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const double m = static_cast<double>(pts.size());
    std::printf(" %s %.2f;", method.c_str(), (m * sxy - sx * sy) / (m * sxx - sx * sx));
  }
  std::cout << std::endl;
  return 0;
}
