// Sparse direct solve with CHOLMOD's supernodal Cholesky (SuiteSparse), symbolic analysis
// reused while the sparsity pattern stays the same.
#include <Eigen/CholmodSupport>
#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/solver/linear_solver.hpp"
#include "sinew/solver/serial_openmp.hpp"

namespace sinew {
namespace {

class CholmodSolver final : public LinearSolver {
 public:
  using LinearSolver::solve;
  std::string name() const override { return "cholmod"; }

  LinearSolveReport solve(const LinearOperator& op, const Eigen::VectorXd& b, Eigen::VectorXd& x, double,
                          const SolverContext&) override {
    if (!op.matrix()) throw Error("CHOLMOD needs an assembled matrix; use pcg with a matrix-free operator", "solver.linear");
    const Eigen::SparseMatrix<double>& A = *op.matrix();
    const SerialOpenMpScope serial_cholmod;
    if (!same_pattern(A)) {
      llt_.analyzePattern(A);
      remember_pattern(A);
    }
    // A PSD-projected Hessian can be singular (clamped modes of unconstrained parts); shift
    // the diagonal slightly and retry rather than give up.
    double shift = 0.0;
    for (int attempt = 0; attempt < 6; ++attempt) {
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
  bool same_pattern(const Eigen::SparseMatrix<double>& A) const {
    return A.rows() == rows_ && A.nonZeros() == nnz_ &&
           std::equal(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1, outer_.begin()) &&
           std::equal(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros(), inner_.begin());
  }
  void remember_pattern(const Eigen::SparseMatrix<double>& A) {
    rows_ = A.rows();
    nnz_ = A.nonZeros();
    outer_.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
    inner_.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  }

  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt_;
  Eigen::Index rows_ = -1, nnz_ = -1;
  std::vector<int> outer_, inner_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_cholmod_solver() { return std::make_unique<CholmodSolver>(); }

}  // namespace sinew
