#pragma once
// Linear solvers behind one interface, so Newton does not care whether a system is solved by
// a sparse Cholesky factorisation, preconditioned CG, or (later) a matrix-free or GPU backend.
#include <Eigen/Sparse>
#include <memory>
#include <string>

#include "sinew/linalg/linear_operator.hpp"
#include "sinew/solver/solver_context.hpp"

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
  // is the relative residual target for iterative solvers (ignored by direct ones). The
  // context (discretisation, lattice, fixed DOFs) is passed on to the preconditioner.
  virtual LinearSolveReport solve(const LinearOperator& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                  double tolerance, const SolverContext& context) = 0;
  // The same for a bare system (empty context).
  LinearSolveReport solve(const LinearOperator& A, const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance) {
    return solve(A, b, x, tolerance, SolverContext{});
  }
};

struct LinearSolverSettings {
  std::string kind = "cholmod";  // "cholmod" | "pcg"
  // pcg only: a name from the preconditioner registry (solver/preconditioner.hpp).
  std::string preconditioner = "block_jacobi";
  int max_iterations = 10000;
  // pcg only: apply the elastic Hessian from kept element matrices instead of assembling it
  // (Problem::set_matrix_free); needs a preconditioner that uses only diagonal blocks.
  bool matrix_free = false;
};

std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverSettings& settings);

}  // namespace sinew
