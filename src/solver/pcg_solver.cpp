#include "sinew/solver/pcg_solver.hpp"

#include <algorithm>
#include <cmath>

#include "sinew/core/error.hpp"

namespace sinew {

PcgSolver::PcgSolver(std::unique_ptr<Preconditioner> preconditioner, int max_iterations)
    : preconditioner_(std::move(preconditioner)), max_iterations_(max_iterations) {
  if (!preconditioner_) throw Error("PCG needs a preconditioner", "solver.linear");
}

std::string PcgSolver::name() const {
  std::string n = "pcg-" + preconditioner_->name();
  std::replace(n.begin(), n.end(), '_', '-');
  return n;
}

LinearSolveReport PcgSolver::solve(const LinearOperator& op, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                   double tolerance, const SolverContext& context) {
  if (op.rows() % 3 != 0) throw Error("PCG expects 3 DOFs per vertex", "solver.linear");
  if (!context.fixed.empty() && static_cast<Eigen::Index>(context.fixed.size()) != op.rows())
    throw Error("the fixed-DOF mask does not match the system's size", "solver.linear");
  const Eigen::Index n = op.rows();
  x.setZero(n);
  const double b_norm = b.norm();
  if (b_norm == 0.0) return {0, 0.0, true};
  Preconditioner& M = *preconditioner_;
  M.setup(op, context);
  Eigen::VectorXd r = b, z(n), p(n), Ap(n);
  M.apply(r, z);
  p = z;
  double rz = r.dot(z);
  const double threshold = tolerance * b_norm;
  double r_norm = b_norm;
  int k = 0;
  while (k < max_iterations_ && r_norm > threshold) {
    op.apply(p, Ap);
    const double pAp = p.dot(Ap);
    // The projected Hessian is positive semi-definite; a direction of zero or negative
    // curvature (round-off on a singular system) ends the solve with the iterate so far.
    if (!(pAp > 0.0)) break;
    const double alpha = rz / pAp;
    x.noalias() += alpha * p;
    r.noalias() -= alpha * Ap;
    r_norm = r.norm();
    ++k;
    if (r_norm <= threshold) break;
    M.apply(r, z);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return {k, r_norm / b_norm, r_norm <= threshold};
}

}  // namespace sinew
