#pragma once
// Preconditioned conjugate gradients over a LinearOperator with any Preconditioner. Written on
// the operator (not on Eigen::ConjugateGradient, which needs the assembled matrix and multiplies
// with it on one core) so that the product runs in parallel through SparseOperator::apply and a
// matrix-free operator can use the same solver.
#include <memory>

#include "sinew/solver/linear_solver.hpp"
#include "sinew/solver/preconditioner.hpp"

namespace sinew {

class PcgSolver final : public LinearSolver {
 public:
  PcgSolver(std::unique_ptr<Preconditioner> preconditioner, int max_iterations);
  using LinearSolver::solve;
  // "pcg-" and the preconditioner's name with '-' for '_' ("pcg-block-jacobi").
  std::string name() const override;
  // PCG from x = 0 (Newton directions are solved afresh); stops when
  // ||b - A x|| <= tolerance ||b||, as Eigen's CG does. The preconditioner is set up once per
  // solve with A and the context; a non-empty fixed mask must have one flag per row.
  LinearSolveReport solve(const LinearOperator& A, const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
                          const SolverContext& context) override;
  Preconditioner& preconditioner() { return *preconditioner_; }

 private:
  std::unique_ptr<Preconditioner> preconditioner_;
  int max_iterations_;
};

}  // namespace sinew
