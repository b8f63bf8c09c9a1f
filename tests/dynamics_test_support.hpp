#pragma once
// Finite-difference checks of a Form's gradient and Hessian, shared by the dynamics, contact and
// rig tests.
#include <gtest/gtest.h>

#include <cmath>

#include "sinew/forms/form.hpp"

namespace sinew::testing_support {

struct FormDerivativeErrors {
  double gradient = 0.0;  // relative, ||g - g_fd|| / ||g||
  double hessian = 0.0;   // relative, ||K - K_fd|| / ||K||
  double asymmetry = 0.0;
};

// Central differences of the value (for the gradient) and of the gradient (for the Hessian).
inline FormDerivativeErrors form_derivative_errors(const Form& form, const Eigen::VectorXd& x, Eigen::Index vertices,
                                                   double step = 1e-6) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  form.add_gradient(x, g);
  std::vector<std::vector<int>> cliques;
  for (int v = 0; v < vertices; ++v) cliques.push_back({v});
  form.couplings(cliques);
  BlockHessian H(vertices, cliques);
  form.add_hessian(x, H);
  const Eigen::MatrixXd K(H.matrix());
  Eigen::VectorXd g_fd(x.size());
  Eigen::MatrixXd K_fd(x.size(), x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd xp = x, xm = x;
    xp(i) += step;
    xm(i) -= step;
    g_fd(i) = (form.value(xp) - form.value(xm)) / (2 * step);
    Eigen::VectorXd gp = Eigen::VectorXd::Zero(x.size()), gm = gp;
    form.add_gradient(xp, gp);
    form.add_gradient(xm, gm);
    K_fd.col(i) = (gp - gm) / (2 * step);
  }
  FormDerivativeErrors e;
  e.gradient = (g - g_fd).norm() / std::max(g.norm(), 1e-300);
  e.hessian = (K - K_fd).norm() / std::max(K.norm(), 1e-300);
  e.asymmetry = (K - K.transpose()).norm() / std::max(K.norm(), 1e-300);
  return e;
}

// Per-entry central differences at x: the value's derivative against the gradient g, and the
// gradient's derivative against the Hessian K, both as the caller assembled them.
inline void expect_derivatives_match_per_entry(const Form& form, const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                                               const Eigen::MatrixXd& K, double eps = 1e-6) {
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd xp = x, xm = x;
    xp(i) += eps;
    xm(i) -= eps;
    EXPECT_NEAR((form.value(xp) - form.value(xm)) / (2 * eps), g(i), 1e-6 * (1.0 + std::abs(g(i)))) << "DOF " << i;
    Eigen::VectorXd gp = Eigen::VectorXd::Zero(x.size()), gm = gp;
    form.add_gradient(xp, gp);
    form.add_gradient(xm, gm);
    EXPECT_LE(((gp - gm) / (2 * eps) - K.col(i)).norm(), 1e-6 * (1.0 + K.col(i).norm())) << "DOF " << i;
  }
}

}  // namespace sinew::testing_support
