// Timing of the design tools (paper section 4; docs/maths.md §5, §6):
// factorization, response precompute (full and lazy bases), update time for
// 1, 10 and all boundary vertices moved, and the cost of adding constraints
// by block elimination against factoring the augmented matrix with LU.
//
//   edit_bench MESH [conformal|authalic|mixed] [reps]
//
// Prints one line per measurement; times are medians over `reps` runs.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>

#include "bench_timing.h"
#include "weights/assemble.h"
#include "intrinsic/boundary_editor.h"
#include "intrinsic/error.h"
#include "intrinsic/io.h"

using namespace intrinsic;

namespace {

using intrinsic::bench::median;
using intrinsic::bench::ms_since;

std::vector<FixedVertex> moved(const std::vector<FixedVertex>& boundary, int k, std::mt19937& rng, double amount) {
  std::vector<FixedVertex> b = boundary;
  std::shuffle(b.begin(), b.end(), rng);
  b.resize(k);
  std::uniform_real_distribution<double> d(-amount, amount);
  for (FixedVertex& fv : b) fv.uv += Eigen::Vector2d(d(rng), d(rng));
  return b;
}

void bench_updates(Parameterizer& p, BasisMode basis, int reps, int resolve_above) {
  EditOptions eo;
  eo.basis = basis;
  eo.resolve_above = resolve_above;
  const char* name = basis == BasisMode::Full ? "full" : "lazy";
  try {
    BoundaryEditor editor(p, eo);
    std::printf("%s basis: precompute %.1f ms, %d responses, %.1f MiB (resolve above %d)\n", name,
                editor.precompute_ms(), editor.responses(), editor.basis_bytes() / 1048576.0, resolve_above);
    std::mt19937 rng(1);
    const int nb = static_cast<int>(editor.boundary().size());
    for (int k : {1, 10, nb}) {
      // The same k vertices dragged `reps` times: the first drag computes
      // lazy responses, the rest reuse them.
      const std::vector<FixedVertex> chosen = moved(editor.boundary(), k, rng, 0.0);
      std::vector<double> first, later;
      for (int r = 0; r <= reps; ++r) {
        std::vector<FixedVertex> m = chosen;
        for (FixedVertex& fv : m) fv.uv += Eigen::Vector2d(1e-3 * (r + 1), -1e-3 * (r + 1));
        editor.move(m);
        (r == 0 ? first : later).push_back(editor.last_update().ms);
      }
      std::printf("  %s k=%-5d first %.3f ms, then median %.3f ms%s\n", name, k, first[0], median(later),
                  editor.last_update().resolved ? " (re-solved)" : " (superposed)");
    }
  } catch (const Error& e) {
    std::printf("%s basis: refused: %s\n", name, e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: edit_bench MESH [conformal|authalic|mixed] [reps]\n");
    return 1;
  }
  const std::string method = argc > 2 ? argv[2] : "conformal";
  const int reps = argc > 3 ? std::atoi(argv[3]) : 7;
  auto t0 = std::chrono::steady_clock::now();
  const Mesh mesh = make_mesh(read_mesh(argv[1]));
  std::printf("%s: %d vertices, read+validate %.0f ms, method %s\n", argv[1], static_cast<int>(mesh.V.rows()),
              ms_since(t0), method.c_str());
  ParamOptions o;
  o.weights.method = parse_method(method);
  if (o.weights.method == Method::Mixed) { o.weights.lambda = 0.5; o.weights.mu = 0.5; }
  t0 = std::chrono::steady_clock::now();
  Parameterizer p(mesh, o);
  std::printf("construct (assemble + factor + first solve) %.1f ms, solver %s\n", ms_since(t0),
              solvers_name(p.solve().solvers).c_str());
  // A fresh full solve with the kept factorization, for reference.
  {
    std::vector<double> t;
    std::vector<FixedVertex> b = p.boundary();
    for (int r = 0; r < reps; ++r) {
      b[0].uv.x() += 1e-3;
      const auto s = std::chrono::steady_clock::now();
      p.solve_with_boundary(b);
      t.push_back(ms_since(s));
    }
    std::printf("solve_with_boundary (same fixed set, 2 rhs): median %.2f ms, factorizations %d\n", median(t),
                p.factorizations());
  }
  bench_updates(p, BasisMode::Full, reps, 1 << 30);
  bench_updates(p, BasisMode::Lazy, reps, 64);
  bench_updates(p, BasisMode::Lazy, reps, 1 << 30);

  // Constraints: 10 interior points, by block elimination (kept factor) and
  // by factoring the augmented matrix [K_II C^T; C 0] with sparse LU.
  Constraints c;
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> face(0, static_cast<int>(mesh.F.rows()) - 1);
  const MatrixX2d uv = p.solve().UV;
  while (c.points.size() < 10) {
    const int f = face(rng);
    bool interior = true;
    for (int k = 0; k < 3; ++k) interior = interior && !mesh.topology.is_boundary[mesh.F(f, k)];
    if (!interior) continue;
    Eigen::Vector2d x = (uv.row(mesh.F(f, 0)) + uv.row(mesh.F(f, 1)) + uv.row(mesh.F(f, 2))).transpose() / 3;
    c.points.push_back({SurfacePoint::in_face(f, Eigen::Vector3d::Constant(1.0 / 3)), x + Eigen::Vector2d(0.01, 0), ""});
  }
  t0 = std::chrono::steady_clock::now();
  p.set_constraints(c);
  const double t_set = ms_since(t0);
  t0 = std::chrono::steady_clock::now();
  p.solve();
  std::printf("10 point constraints, block elimination: set %.1f ms, solve %.2f ms\n", t_set, ms_since(t0));

  const SparseMatrix K = assemble_weight_matrix(mesh.V, mesh.F, o.weights);
  std::vector<char> fixed(mesh.V.rows(), 0);
  for (const FixedVertex& fv : p.boundary()) fixed[fv.vertex] = 1;
  const Partition part = partition(static_cast<int>(mesh.V.rows()), fixed, mesh.topology.is_used);
  SparseMatrix A, KIB;
  split_matrix(K, part, A, KIB);
  const int N = static_cast<int>(A.rows()), m = 10;
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) t.emplace_back(it.row(), j, it.value());
  for (int r = 0; r < m; ++r)
    for (int k = 0; k < 3; ++k) {
      const int col = part.free_index[mesh.F(c.points[r].point.face, k)];
      t.emplace_back(N + r, col, 1.0 / 3);
      t.emplace_back(col, N + r, 1.0 / 3);
    }
  SparseMatrix aug(N + m, N + m);
  aug.setFromTriplets(t.begin(), t.end());
  for (SolverKind kind : {SolverKind::Umfpack, SolverKind::EigenLU}) {
    if (!solver_available(kind)) continue;
    LinearSolver lu(kind, false);
    t0 = std::chrono::steady_clock::now();
    lu.factor(aug);
    std::printf("augmented %d x %d, %s factor: %.1f ms\n", N + m, N + m, solver_name(kind).c_str(), ms_since(t0));
  }
  return 0;
}
