// Sparse direct solve with CHOLMOD's supernodal Cholesky (SuiteSparse), symbolic analysis
// reused while the sparsity pattern stays the same.
#include <Eigen/CholmodSupport>
#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/linalg/pattern_memo.hpp"
#include "sinew/solver/linear_solver.hpp"
#include "sinew/solver/serial_openmp.hpp"

namespace sinew {
namespace {

class CholmodSolver final : public LinearSolver {
 public:
  using LinearSolver::solve;
  // A failed factorisation (an indefinite true Hessian, a singular projected one) is handled
  // here, by a fallback or a shift: CHOLMOD must not print its own warning to stdout.
  CholmodSolver() { llt_.cholmod().print = 0; }
  std::string name() const override { return "cholmod"; }

  LinearSolveReport solve(const LinearOperator& op, const Eigen::VectorXd& b, Eigen::VectorXd& x, double,
                          const SolverContext& context) override {
    if (!op.matrix()) throw Error("CHOLMOD needs an assembled matrix; use pcg with a matrix-free operator", "solver.linear");
    const Eigen::SparseMatrix<double>& A = *op.matrix();
    const SerialOpenMpScope serial_cholmod;
    if (!pattern_.same_or_remember(A, op.pattern_id())) llt_.analyzePattern(A);
    // A PSD-projected Hessian can be singular (clamped modes of unconstrained parts); shift
    // the diagonal slightly and retry rather than give up.
    double shift = 0.0;
    // An indefinite true Hessian is not shifted into a different matrix: its failure is the answer.
    const int attempts = context.may_be_indefinite ? 1 : 6;
    for (int attempt = 0; attempt < attempts; ++attempt) {
      llt_.setShift(shift);
      llt_.factorize(A);
      if (llt_.info() == Eigen::Success) {
        x = llt_.solve(b);
        if (llt_.info() == Eigen::Success && x.allFinite()) {
          const double rel = (A * x - b).norm() / std::max(b.norm(), 1e-300);
          return {1, rel, true};
        }
      }
      const double diag = A.diagonal().cwiseAbs().maxCoeff();
      shift = shift == 0.0 ? 1e-10 * diag : shift * 100.0;
    }
    return {1, 1.0, false};
  }

 private:
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt_;
  PatternMemo pattern_;  // the pattern llt_ was analysed for
};

}  // namespace

std::unique_ptr<LinearSolver> make_cholmod_solver() { return std::make_unique<CholmodSolver>(); }

}  // namespace sinew
