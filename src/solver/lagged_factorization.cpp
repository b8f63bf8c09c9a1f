#include "sinew/solver/lagged_factorization.hpp"

#include <Eigen/CholmodSupport>
#include <chrono>

#include "sinew/core/error.hpp"
#include "sinew/linalg/linear_operator.hpp"

namespace sinew {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

}  // namespace

struct LaggedFactorization::Cholmod {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
};

LaggedFactorization::LaggedFactorization() : cholmod_(std::make_unique<Cholmod>()) {}
LaggedFactorization::~LaggedFactorization() = default;

void LaggedFactorization::use(const Eigen::SparseMatrix<double>& M, const FactorizationReuse& reuse,
                              Counters& counters) {
  current_ = &M;
  reuse_ = reuse;
  exact_ = false;
  if (!reuse.enabled || !valid_ || cg_iterations_since_ >= cg_iterations_per_factorization_) refactor(counters);
}

void LaggedFactorization::refactor(Counters& counters) {
  const auto t = Clock::now();
  auto& llt = cholmod_->llt;
  if (!analysed_) llt.analyzePattern(*current_);
  analysed_ = true;
  llt.factorize(*current_);
  if (llt.info() != Eigen::Success) {
    llt.analyzePattern(*current_);  // the pattern can change when the warped stiffness cancels entries
    llt.factorize(*current_);
  }
  valid_ = llt.info() == Eigen::Success;
  if (!valid_) throw Error("backward-Euler or SQP matrix is not positive definite", "constrained stepper");
  const cholmod_common& c = llt.cholmod();
  cg_iterations_per_factorization_ = c.fl / (4.0 * c.lnz + 2.0 * static_cast<double>(current_->nonZeros()));
  cg_iterations_since_ = 0;
  columns_.clear();
  exact_ = true;
  ++counters.factorizations;
  counters.factor_seconds += since(t);
}

void LaggedFactorization::solve(const Eigen::VectorXd& r, Eigen::VectorXd& out, bool guess, Counters& counters) {
  const auto t = Clock::now();
  const double factor_seconds_before = counters.factor_seconds;
  if (exact_ || !preconditioned_cg(r, out, guess, counters)) {
    if (!exact_) refactor(counters);  // the lagged factorisation no longer preconditions well
    out = cholmod_->llt.solve(r);
  }
  counters.solve_seconds += since(t) - (counters.factor_seconds - factor_seconds_before);
}

bool LaggedFactorization::preconditioned_cg(const Eigen::VectorXd& r, Eigen::VectorXd& out, bool guess,
                                            Counters& counters) {
  const auto& llt = cholmod_->llt;
  const Eigen::Index n = r.size();
  const double r_norm = r.norm();
  if (!guess || r_norm == 0.0) out.setZero(n);
  if (r_norm == 0.0) return true;
  const double target = reuse_.cg_tolerance * r_norm;
  const SparseOperator op(*current_);
  Eigen::VectorXd res = r, Ap(n);
  if (guess) {
    op.apply(out, Ap);
    res -= Ap;
  }
  if (res.norm() <= target) return true;
  Eigen::VectorXd z = llt.solve(res), p = z;
  double rz = res.dot(z);
  for (int it = 0; it < reuse_.max_cg_iterations; ++it) {
    op.apply(p, Ap);
    const double alpha = rz / p.dot(Ap);
    out += alpha * p;
    res -= alpha * Ap;
    ++counters.cg_iterations;
    ++cg_iterations_since_;
    if (res.norm() <= target) return true;
    z = llt.solve(res);
    const double rz_next = res.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return false;
}

Eigen::MatrixXd LaggedFactorization::apply_inverse(const Eigen::MatrixXd& B) const { return cholmod_->llt.solve(B); }

}  // namespace sinew
