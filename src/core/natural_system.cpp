// The natural conformal map's system (paper section 4.2, eq. 7;
// docs/maths.md §3): no boundary is fixed; the minimiser of E_D - A with two
// pinned vertices, which equals LSCM (Levy et al. 2002) with the same pins.
#include "core/natural_system.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <numeric>
#include <set>

#include "weights/assemble.h"
#include "intrinsic/error.h"
#include "util/parallel_for.h"

namespace intrinsic {
namespace {

// The user's pins, checked: at least two, existing used vertices, each once,
// finite, not all at one point (the minimiser would then be the constant map).
void check_pins(const Mesh& mesh, const std::vector<FixedVertex>& pins) {
  if (pins.size() < 2)
    throw_usage("the natural map needs at least two pins (fixing translation, rotation and scale); got " +
                std::to_string(pins.size()));
  std::set<int> seen;
  for (const FixedVertex& p : pins) {
    if (p.vertex < 0 || p.vertex >= mesh.V.rows())
      throw_input("pin on vertex " + std::to_string(p.vertex) + ", which does not exist (the mesh has " +
                  std::to_string(mesh.V.rows()) + " vertices)");
    if (!mesh.topology.is_used[p.vertex])
      throw_input("pin on vertex " + std::to_string(p.vertex) + ", which no face uses");
    if (!seen.insert(p.vertex).second) throw_usage("vertex " + std::to_string(p.vertex) + " is pinned twice");
    if (!p.uv.allFinite()) throw_usage("pin on vertex " + std::to_string(p.vertex) + " has a non-finite position");
  }
  bool all_same = true;
  for (const FixedVertex& p : pins) all_same = all_same && p.uv == pins[0].uv;
  if (all_same) throw_usage("the pins are all at the same position; the map would collapse to a point");
}

}  // namespace

SparseMatrix area_coupling(int n, const std::vector<std::vector<int>>& loops) {
  std::vector<Eigen::Triplet<double>> t;
  for (const std::vector<int>& loop : loops)
    for (size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k], b = loop[(k + 1) % loop.size()];
      t.emplace_back(a, b, 1.0);
      t.emplace_back(b, a, -1.0);
    }
  SparseMatrix B(n, n);
  B.setFromTriplets(t.begin(), t.end());
  B.prune(0.0);  // a two-vertex loop's half-edges cancel
  return B;
}

// Column offsets first (column j and n + j each hold K's column j and B's),
// then the columns filled in parallel: each writes its own range.
SparseMatrix real_form_matrix(const SparseMatrix& K, const SparseMatrix& B) {
  const Eigen::Index n = K.rows();
  SparseMatrix Q(2 * n, 2 * n);
  Q.resizeNonZeros(2 * (K.nonZeros() + B.nonZeros()));
  int* outer = Q.outerIndexPtr();
  int* rows = Q.innerIndexPtr();
  double* values = Q.valuePtr();
  auto column_size = [](const SparseMatrix& M, Eigen::Index j) {
    return static_cast<int>(M.isCompressed() ? M.outerIndexPtr()[j + 1] - M.outerIndexPtr()[j]
                                             : M.innerNonZeroPtr()[j]);
  };
  outer[0] = 0;
  for (Eigen::Index j = 0; j < n; ++j) outer[j + 1] = outer[j] + column_size(K, j) + column_size(B, j);
  for (Eigen::Index j = 0; j < n; ++j) outer[n + j + 1] = outer[n + j] + column_size(K, j) + column_size(B, j);
  detail::parallel_for(n, [&](std::int64_t begin, std::int64_t end) {
    for (std::int64_t j = begin; j < end; ++j) {
      auto append = [&](Eigen::Index& out, const SparseMatrix& M, Eigen::Index row_shift, double sign) {
        for (SparseMatrix::InnerIterator it(M, j); it; ++it) {
          rows[out] = static_cast<int>(it.row() + row_shift);
          values[out++] = sign * it.value();
        }
      };
      Eigen::Index u = outer[j], v = outer[n + j];
      append(u, K, 0, 1);   // u column: K over B
      append(u, B, n, 1);
      append(v, B, 0, -1);  // v column: -B over K
      append(v, K, n, 1);
    }
  });
  return Q;
}

SparseMatrix assemble_natural_system(const Mesh& mesh) {
  WeightOptions conformal;
  conformal.method = Method::Conformal;
  const SparseMatrix K = assemble_weight_matrix(mesh.V, mesh.F, conformal);
  return real_form_matrix(K, area_coupling(static_cast<int>(mesh.V.rows()), mesh.topology.boundary_loops));
}

std::pair<int, int> default_pin_pair(const Mesh& mesh) {
  const Topology& t = mesh.topology;
  if (t.component_loops.empty() || t.component_loops[0].empty())
    throw_input("the surface is closed (no boundary): nothing to pin by default");
  return farthest_pair(mesh.V, t.boundary_loops[t.component_loops[0][0]]);
}

std::pair<int, int> farthest_pair(const MatrixX3d& V, std::vector<int> b) {
  if (b.size() < 2) throw_input("fewer than two boundary vertices: nothing to pin by default");
  std::sort(b.begin(), b.end());
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int v : b) c += V.row(v).transpose();
  c /= static_cast<double>(b.size());
  // Visit vertices by decreasing distance to the centroid: once r_i + r_j
  // cannot beat the best pair, no later j (nor, for j = i+1, later i) can.
  std::vector<double> r(b.size());
  for (size_t k = 0; k < b.size(); ++k) r[k] = (V.row(b[k]).transpose() - c).norm();
  std::vector<int> order(b.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return r[x] > r[y]; });
  // Distances within kTie of the largest are ties, broken by the smallest
  // index pair: exact comparison would let rounding pick between mirror-image
  // pairs, so scaling the input by 1e-6 could move the pins.
  constexpr double kTie = 1e-12;
  double best = -1;
  std::vector<std::pair<double, std::pair<int, int>>> near_best;  // pairs within kTie of the best so far
  for (size_t i = 0; i + 1 < order.size(); ++i) {
    const int p = order[i];
    const double bound = std::sqrt(std::max(best, 0.0)) * (1 - 2 * kTie);
    if (r[p] + r[order[i + 1]] < bound) break;
    const Eigen::Vector3d xp = V.row(b[p]);
    for (size_t j = i + 1; j < order.size(); ++j) {
      const int q = order[j];
      if (r[p] + r[q] < bound) break;
      const double d2 = (V.row(b[q]).transpose() - xp).squaredNorm();
      if (d2 < best * (1 - kTie)) continue;
      best = std::max(best, d2);
      near_best.push_back({d2, {std::min(b[p], b[q]), std::max(b[p], b[q])}});
    }
  }
  std::pair<int, int> pair{INT_MAX, INT_MAX};
  for (const auto& [d2, cand] : near_best)
    if (d2 >= best * (1 - kTie)) pair = std::min(pair, cand);
  return pair;
}

void check_natural_method(const WeightOptions& w) {
  const bool conformal =
      w.method == Method::Conformal || (w.method == Method::Mixed && w.mu == 0 && w.lambda != 0);
  if (!conformal)
    throw_usage("the natural boundary needs the conformal method: its condition (eq. 7) comes from the conformal "
                "energy E_D - A, and the authalic weights derive from no known energy (paper section 4.2)");
}

double natural_hole_weight(const WeightOptions& w) {
  switch (w.method) {
    case Method::Conformal: return 1.0;
    case Method::Mixed: return w.lambda;
    default: return 0.0;
  }
}

bool solves_natural_holes(const Mesh& mesh, const ParamOptions& o) {
  return o.holes == HoleRule::Natural && mesh.topology.component_loops.at(0).size() > 1 &&
         natural_hole_weight(o.weights) != 0;
}

std::vector<FixedVertex> natural_pins(const Mesh& mesh, const ParamOptions& o) {
  std::vector<FixedVertex> pins = o.pins;
  if (pins.empty()) {
    const auto [a, b] = default_pin_pair(mesh);
    const double d = (mesh.V.row(a) - mesh.V.row(b)).norm();
    pins = {{a, Eigen::Vector2d(0, 0)}, {b, Eigen::Vector2d(d, 0)}};
  } else {
    check_pins(mesh, pins);
  }
  return pins;
}

}  // namespace intrinsic
