#pragma once
// Linear solvers behind one interface, so Newton does not care whether a system is solved by
// a sparse Cholesky factorisation, preconditioned CG, or (later) a matrix-free or GPU backend.
#include <Eigen/Sparse>
#include <memory>
#include <string>

#include "sinew/linalg/linear_operator.hpp"

namespace sinew {

struct LinearSolveReport {
  int iterations = 0;        // CG iterations (1 for a direct solve)
  double relative_residual = 0.0;
  bool converged = false;
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  virtual std::string name() const = 0;
  // Solves A x = b for symmetric positive (semi-)definite A. The sparsity pattern of A may be
  // reused between calls; the symbolic analysis is redone only when it changes. `tolerance`
  // is the relative residual target for iterative solvers (ignored by direct ones).
  virtual LinearSolveReport solve(const LinearOperator& A, const Eigen::VectorXd& b,
                                  Eigen::VectorXd& x, double tolerance) = 0;
};

enum class Preconditioner { Jacobi, BlockJacobi3 };

struct LinearSolverSettings {
  std::string kind = "cholmod";  // "cholmod" | "pcg"
  Preconditioner preconditioner = Preconditioner::BlockJacobi3;
  int max_iterations = 10000;
};

std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverSettings& settings);

}  // namespace sinew
