// Cheap checks run only after a solve failed, to name the likely cause.
#include "core/failure_diagnosis.h"

#include <algorithm>
#include <cmath>

#include "weights/assemble.h"
#include "intrinsic/error.h"

namespace intrinsic::detail {
namespace {

// "vertex 12 and 3 other free vertices are not tied ..." or "".
std::string untied_free_vertices(const Mesh& mesh, const SparseMatrix& K, const std::vector<FixedVertex>& fixed) {
  std::vector<std::vector<int>> adjacent(K.rows());
  for (int c = 0; c < K.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(K, c); it; ++it)
      if (it.row() != it.col() && it.value() != 0) adjacent[it.row()].push_back(static_cast<int>(it.col()));
  std::vector<char> reached(K.rows(), 0);
  std::vector<int> queue;
  for (const FixedVertex& fv : fixed)
    if (fv.vertex >= 0 && fv.vertex < K.rows() && !reached[fv.vertex]) reached[fv.vertex] = 1, queue.push_back(fv.vertex);
  for (size_t k = 0; k < queue.size(); ++k)
    for (int w : adjacent[queue[k]])
      if (!reached[w]) reached[w] = 1, queue.push_back(w);
  int cut_off = 0, first = -1;
  for (int v = 0; v < K.rows(); ++v)
    if (mesh.topology.is_used[v] && !reached[v] && cut_off++ == 0) first = v;
  if (cut_off == 0) return "";
  return "vertex " + std::to_string(first) +
         (cut_off > 1 ? " and " + std::to_string(cut_off - 1) + " other free vertices are" : " is") +
         " not tied to any fixed vertex by a nonzero weight";
}

// The face with the smallest area / longest edge squared, if below 1e-6.
std::string nearly_degenerate_face(const Mesh& mesh) {
  double worst = INFINITY;
  int worst_face = -1;
  for (int f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d x0 = mesh.V.row(mesh.F(f, 0)), x1 = mesh.V.row(mesh.F(f, 1)), x2 = mesh.V.row(mesh.F(f, 2));
    const double longest = std::max({(x1 - x0).squaredNorm(), (x2 - x1).squaredNorm(), (x0 - x2).squaredNorm()});
    const double ratio = (x1 - x0).cross(x2 - x0).norm() / longest;
    if (ratio < worst) worst = ratio, worst_face = f;
  }
  if (!(worst < 1e-6)) return "";
  return mesh.describe_face(worst_face) + " is nearly degenerate (area / longest edge squared " +
         short_number(worst) + ")";
}

}  // namespace

std::string likely_cause(const Mesh& mesh, const WeightOptions& weights, const std::vector<FixedVertex>& fixed) {
  const SparseMatrix K = assemble_weight_matrix(mesh.V, mesh.F, weights);
  std::vector<std::string> causes;
  if (!std::all_of(K.valuePtr(), K.valuePtr() + K.nonZeros(), [](double x) { return std::isfinite(x); }))
    causes.push_back("some weights are not finite");
  for (const std::string& c : {untied_free_vertices(mesh, K, fixed), nearly_degenerate_face(mesh)})
    if (!c.empty()) causes.push_back(c);
  std::string out;
  for (const std::string& c : causes) out += (out.empty() ? "; likely cause: " : "; ") + c;
  return out;
}

}  // namespace intrinsic::detail
