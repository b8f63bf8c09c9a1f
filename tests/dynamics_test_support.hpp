#pragma once
// Finite-difference checks of a Form's gradient and Hessian, shared by the dynamics, contact and
// rig tests: thin views of the library's checker (forms/derivative_check.hpp).
#include <gtest/gtest.h>

#include <cmath>

#include "sinew/forms/derivative_check.hpp"
#include "sinew/forms/form.hpp"

namespace sinew::testing_support {

struct FormDerivativeErrors {
  double gradient = 0.0;  // relative, ||g - g_fd|| / ||g||
  double hessian = 0.0;   // relative, ||K - K_fd|| / ||K|| (the exact Hessian)
  double asymmetry = 0.0;
};

// Central differences of the value (for the gradient) and of the gradient (for the Hessian)
// along every DOF, with an absolute step.
inline FormDerivativeErrors form_derivative_errors(const Form& form, const Eigen::VectorXd& x, Eigen::Index vertices,
                                                   double step = 1e-6) {
  EXPECT_EQ(x.size(), 3 * vertices);
  FormCheckOptions o;
  o.step = step;
  o.max_coordinate_dofs = x.size();
  const FormCheck c = check_form(form, x, o);
  EXPECT_TRUE(c.coordinate);
  return {c.gradient_error, c.hessian_error, c.asymmetry};
}

// Per-entry central differences at x: the value's derivative against the gradient g, and the
// gradient's derivative against the Hessian K, both as the caller assembled them.
inline void expect_derivatives_match_per_entry(const Form& form, const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                                               const Eigen::MatrixXd& K, double eps = 1e-6) {
  FormCheckOptions o;
  o.step = eps;
  o.max_coordinate_dofs = x.size();
  const FormDifferences d = form_differences(form, x, o);
  ASSERT_TRUE(d.coordinate);
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    EXPECT_NEAR(d.gradient_fd(i), g(i), 1e-6 * (1.0 + std::abs(g(i)))) << "DOF " << i;
    EXPECT_LE((d.hessian_fd.col(i) - K.col(i)).norm(), 1e-6 * (1.0 + K.col(i).norm())) << "DOF " << i;
  }
}

}  // namespace sinew::testing_support
