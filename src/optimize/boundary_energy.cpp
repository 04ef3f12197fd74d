// The energies boundary optimization minimises and their gradients with
// respect to every UV: edge-length and area distortion (paper section 5.1)
// and the symmetric Dirichlet energy (an injectivity barrier: infinite on a
// flipped triangle).
#include <cmath>
#include <limits>

#include "intrinsic/boundary_optimization.h"
#include "intrinsic/error.h"
#include "intrinsic/choice.h"
#include "intrinsic/metrics.h"

namespace intrinsic {

BoundaryEnergy parse_boundary_energy(const std::string& name) {
  return parse_choice<BoundaryEnergy>(name, "optimize-boundary");
}

GradientRoute parse_gradient_route(const std::string& name) { return parse_choice<GradientRoute>(name, "gradient"); }

Descent parse_descent(const std::string& name) { return parse_choice<Descent>(name, "descent"); }

std::string boundary_energy_name(BoundaryEnergy e) { return choice_name(e); }

std::string gradient_route_name(GradientRoute r) { return choice_name(r); }

std::string descent_name(Descent d) { return choice_name(d); }

namespace {

double edge_energy(const MatrixX3d& V, const Eigen::MatrixX2i& E, const MatrixX2d& UV, MatrixX2d* g) {
  double e = 0;
  for (int k = 0; k < E.rows(); ++k) {
    const int i = E(k, 0), j = E(k, 1);
    const double L2 = (V.row(i) - V.row(j)).squaredNorm();
    const Eigen::RowVector2d d = UV.row(i) - UV.row(j);
    const double r = d.squaredNorm() / L2 - 1;
    e += r * r;
    if (g) {
      const Eigen::RowVector2d gi = 4 * r / L2 * d;
      g->row(i) += gi;
      g->row(j) -= gi;
    }
  }
  return e;
}

double area_energy_grad(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, MatrixX2d* g) {
  double e = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d x0 = V.row(F(f, 0)), x1 = V.row(F(f, 1)), x2 = V.row(F(f, 2));
    const double A3 = 0.5 * (x1 - x0).cross(x2 - x0).norm();
    const Eigen::RowVector2d u[3] = {UV.row(F(f, 0)), UV.row(F(f, 1)), UV.row(F(f, 2))};
    const double A = 0.5 * ((u[1].x() - u[0].x()) * (u[2].y() - u[0].y()) - (u[1].y() - u[0].y()) * (u[2].x() - u[0].x()));
    const double r = A / A3 - 1;
    e += r * r;
    if (g)
      for (int a = 0; a < 3; ++a) {
        const Eigen::RowVector2d& b = u[(a + 1) % 3];
        const Eigen::RowVector2d& c = u[(a + 2) % 3];
        // dA/du_a = 1/2 (y_b - y_c, x_c - x_b)
        g->row(F(f, a)) += 2 * r / A3 * 0.5 * Eigen::RowVector2d(b.y() - c.y(), c.x() - b.x());
      }
  }
  return e;
}

double dirichlet_energy(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, MatrixX2d* g) {
  double e = 0;
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d x0 = V.row(F(f, 0)), x1 = V.row(F(f, 1)), x2 = V.row(F(f, 2));
    const Eigen::Vector3d e1 = x1 - x0, e2 = x2 - x0, n = e1.cross(e2);
    const double l1 = e1.norm(), A3 = 0.5 * n.norm();
    Eigen::Matrix2d P;
    P << l1, e1.dot(e2) / l1, 0, n.norm() / l1;
    const Eigen::Matrix2d G = P.inverse();
    Eigen::Matrix2d Q;
    Q.col(0) = (UV.row(F(f, 1)) - UV.row(F(f, 0))).transpose();
    Q.col(1) = (UV.row(F(f, 2)) - UV.row(F(f, 0))).transpose();
    const Eigen::Matrix2d J = Q * G;
    const double d = J.determinant();
    if (!(d > 0)) return std::numeric_limits<double>::infinity();
    const double fro = J.squaredNorm();
    e += A3 * fro * (1 + 1 / (d * d));
    if (g) {
      Eigen::Matrix2d cof;  // d det(Q) / dQ
      cof << Q(1, 1), -Q(1, 0), -Q(0, 1), Q(0, 0);
      const Eigen::Matrix2d dQ =
          A3 * (2 * J * G.transpose() * (1 + 1 / (d * d)) - 2 * fro / (d * d * d) * G.determinant() * cof);
      g->row(F(f, 1)) += dQ.col(0).transpose();
      g->row(F(f, 2)) += dQ.col(1).transpose();
      g->row(F(f, 0)) -= (dQ.col(0) + dQ.col(1)).transpose();
    }
  }
  return e;
}

}  // namespace

double boundary_energy(const MatrixX3d& V, const MatrixX3i& F, const MatrixX2d& UV, BoundaryEnergy e,
                       MatrixX2d* gradient) {
  return boundary_energy(V, F, e == BoundaryEnergy::EdgeLength ? unique_edges(F) : Eigen::MatrixX2i(), UV, e, gradient);
}

double boundary_energy(const MatrixX3d& V, const MatrixX3i& F, const Eigen::MatrixX2i& edges, const MatrixX2d& UV,
                       BoundaryEnergy e, MatrixX2d* gradient) {
  if (gradient) *gradient = MatrixX2d::Zero(UV.rows(), 2);
  switch (e) {
    case BoundaryEnergy::EdgeLength: return edge_energy(V, edges, UV, gradient);
    case BoundaryEnergy::Area: return area_energy_grad(V, F, UV, gradient);
    case BoundaryEnergy::SymmetricDirichlet: return dirichlet_energy(V, F, UV, gradient);
  }
  return 0;
}

// How the command line, Python and the reports spell these (intrinsic/choice.h).
template <>
ChoiceTable<BoundaryEnergy> choice_table<BoundaryEnergy>() {
  static const Choice<BoundaryEnergy> rows[] = {{BoundaryEnergy::EdgeLength, "edge"},
                                                {BoundaryEnergy::Area, "area"},
                                                {BoundaryEnergy::SymmetricDirichlet, "dirichlet"}};
  return make_choice_table(rows);
}

template <>
ChoiceTable<GradientRoute> choice_table<GradientRoute>() {
  static const Choice<GradientRoute> rows[] = {{GradientRoute::Adjoint, "adjoint"},
                                               {GradientRoute::Responses, "responses"}};
  return make_choice_table(rows);
}

template <>
ChoiceTable<Descent> choice_table<Descent>() {
  static const Choice<Descent> rows[] = {{Descent::LBFGS, "lbfgs"}, {Descent::GradientDescent, "gradient"}};
  return make_choice_table(rows);
}

}  // namespace intrinsic
