#include "sinew/solver/pgs.hpp"

#include <algorithm>
#include <cmath>

namespace sinew {
namespace {

// The admissible interval of row i given the current normal multipliers.
double project(const std::vector<LcpRow>& rows, const Eigen::VectorXd& lambda, Eigen::Index i, double value) {
  const LcpRow& r = rows[i];
  if (r.normal < 0) return std::max(0.0, value);
  const double bound = r.mu * std::max(0.0, lambda(r.normal));
  return std::clamp(value, -bound, bound);
}

}  // namespace

double lcp_residual(const Eigen::MatrixXd& W, const Eigen::VectorXd& q, const std::vector<LcpRow>& rows,
                    const Eigen::VectorXd& lambda) {
  const Eigen::VectorXd w = W * lambda + q;
  double r = 0.0;
  for (Eigen::Index i = 0; i < q.size(); ++i)
    r = std::max(r, std::abs(W(i, i) * (lambda(i) - project(rows, lambda, i, lambda(i) - w(i) / W(i, i)))));
  return r;
}

PgsReport solve_pgs(const Eigen::MatrixXd& W, const Eigen::VectorXd& q, const std::vector<LcpRow>& rows,
                    Eigen::VectorXd& lambda, const PgsSettings& settings) {
  const Eigen::Index m = q.size();
  if (lambda.size() != m) lambda = Eigen::VectorXd::Zero(m);
  PgsReport report;
  if (m == 0) {
    report.converged = true;
    return report;
  }
  Eigen::VectorXd w = W * lambda + q;  // kept current as lambda changes
  for (int it = 1; it <= settings.max_iterations; ++it) {
    double change = 0.0;
    for (Eigen::Index i = 0; i < m; ++i) {
      const double next = project(rows, lambda, i, lambda(i) - w(i) / W(i, i));
      const double delta = next - lambda(i);
      if (delta == 0.0) continue;
      change = std::max(change, std::abs(W(i, i) * delta));
      lambda(i) = next;
      w += W.col(i) * delta;
    }
    report.iterations = it;
    // A sweep that moved nothing by more than the tolerance is a candidate fixed point.
    if (change <= settings.tolerance && lcp_residual(W, q, rows, lambda) <= settings.tolerance) break;
  }
  report.residual = lcp_residual(W, q, rows, lambda);
  report.converged = report.residual <= settings.tolerance;
  return report;
}

}  // namespace sinew
