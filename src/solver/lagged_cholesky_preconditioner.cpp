#include "sinew/solver/lagged_cholesky_preconditioner.hpp"

#include <Eigen/CholmodSupport>
#include <algorithm>

#include "sinew/core/error.hpp"
#include "sinew/solver/serial_openmp.hpp"

namespace sinew {

struct LaggedCholeskyPreconditioner::Cholmod {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
};

LaggedCholeskyPreconditioner::LaggedCholeskyPreconditioner(LaggedCholeskySettings settings)
    : cholmod_(std::make_unique<Cholmod>()), settings_(settings) {}
LaggedCholeskyPreconditioner::~LaggedCholeskyPreconditioner() = default;

void LaggedCholeskyPreconditioner::setup(const LinearOperator& op, const SolverContext&) {
  const Eigen::SparseMatrix<double>* A = op.matrix();
  if (!A) throw Error("needs an assembled matrix (the operator is matrix-free); use jacobi or block_jacobi",
                      "preconditioner lagged_cholesky");
  exact_ = false;
  const bool pattern_changed = !pattern_.same_or_remember(*A, op.pattern_id());
  if (pattern_changed) cholmod_->llt.analyzePattern(*A);
  if (!valid_ || pattern_changed || applications_since_ >= settings_.refresh_cost_factor * refresh_cost_) factorize(*A);
}

void LaggedCholeskyPreconditioner::factorize(const Eigen::SparseMatrix<double>& A) {
  const SerialOpenMpScope serial_cholmod;
  auto& llt = cholmod_->llt;
  // A projected Hessian can be singular (clamped modes of unconstrained parts): shift the
  // diagonal slightly and retry, as the direct solver does.
  double shift = 0.0;
  const double diag = A.diagonal().cwiseAbs().maxCoeff();
  valid_ = false;
  for (int attempt = 0; attempt < 6 && !valid_; ++attempt) {
    llt.setShift(shift);
    llt.factorize(A);
    valid_ = llt.info() == Eigen::Success;
    shift = shift == 0.0 ? 1e-10 * diag : shift * 100.0;
  }
  if (!valid_) throw Error("the matrix could not be factorised (not positive semi-definite)", "preconditioner lagged_cholesky");
  const cholmod_common& c = llt.cholmod();
  refresh_cost_ = c.fl / (4.0 * c.lnz + 2.0 * static_cast<double>(A.nonZeros()));
  applications_since_ = 0;
  exact_ = true;
  ++factorizations_;
}

void LaggedCholeskyPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  const SerialOpenMpScope serial_cholmod;
  z = cholmod_->llt.solve(r);
  ++applications_since_;
}

}  // namespace sinew
