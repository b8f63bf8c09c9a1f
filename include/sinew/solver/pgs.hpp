#pragma once
// Projected Gauss-Seidel for the mixed LCP of paper 001 Eq. 23 with Coulomb friction
// (Cottle, Pang & Stone): find lambda with w = W lambda + q and, per row,
//   unilateral:  0 <= lambda_i  perp  w_i >= 0            (energy limits, contact normals)
//   friction:    -mu lambda_n <= lambda_i <= mu lambda_n, w_i = 0 inside the box, w_i <= 0 at
//                the upper and >= 0 at the lower bound (box approximation of the friction cone,
//                one row per tangent direction, lambda_n the row's normal).
#include <Eigen/Core>
#include <vector>

namespace sinew {

struct LcpRow {
  int normal = -1;    // friction rows: index of their normal row; -1 for a unilateral row
  double mu = 0.0;    // friction coefficient (friction rows)
};

struct PgsSettings {
  int max_iterations = 500;
  double tolerance = 1e-6;  // on the projected residual max_i |W_ii (lambda_i - proj(lambda_i - w_i/W_ii))|
};

struct PgsReport {
  int iterations = 0;
  double residual = 0.0;
  bool converged = false;
};

// Solves in place, warm-started from `lambda` (resized to zero if its size is wrong). W must
// have a positive diagonal.
PgsReport solve_pgs(const Eigen::MatrixXd& W, const Eigen::VectorXd& q, const std::vector<LcpRow>& rows,
                    Eigen::VectorXd& lambda, const PgsSettings& settings);

// The projected residual of lambda (as used for the stopping test).
double lcp_residual(const Eigen::MatrixXd& W, const Eigen::VectorXd& q, const std::vector<LcpRow>& rows,
                    const Eigen::VectorXd& lambda);

}  // namespace sinew
