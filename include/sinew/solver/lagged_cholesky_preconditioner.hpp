#pragma once
// "lagged_cholesky": a sparse Cholesky factorisation (CHOLMOD, supernodal) of an earlier matrix,
// applied as the preconditioner for later ones. While it is of the current matrix PCG converges
// in one iteration; as the matrix drifts PCG needs more, and it is refreshed when the
// preconditioned iterations since the factorisation cost about as much as a new one (rent or
// buy, from CHOLMOD's flop and nonzero counts as in LaggedFactorization, so deterministic), or
// when the sparsity pattern changes. Needs an assembled matrix (LinearOperator::matrix()).
// The SQP/LCP stepper's LaggedFactorization (solver/lagged_factorization.hpp) follows the same
// policy and additionally caches constraint columns.
#include <memory>
#include <vector>

#include "sinew/linalg/pattern_memo.hpp"
#include "sinew/solver/preconditioner.hpp"

namespace sinew {

struct LaggedCholeskySettings {
  // Refresh once the applications since the factorisation exceed this multiple of the
  // factorisation's cost in CG iterations (0: refactorise at every setup, an exact solve).
  double refresh_cost_factor = 1.0;
};

class LaggedCholeskyPreconditioner final : public Preconditioner {
 public:
  explicit LaggedCholeskyPreconditioner(LaggedCholeskySettings settings = {});
  ~LaggedCholeskyPreconditioner() override;
  std::string name() const override { return "lagged_cholesky"; }
  void setup(const LinearOperator& A, const SolverContext& context) override;
  void apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) override;

  // Factorise at the next setup whatever the budget says.
  void invalidate() { valid_ = false; }
  // Whether the factorisation is of the matrix of the last setup.
  bool exact() const { return exact_; }
  int factorizations() const { return factorizations_; }
  // Applications (about one per CG iteration) since the last factorisation.
  int applications_since_factorization() const { return applications_since_; }

 private:
  void factorize(const Eigen::SparseMatrix<double>& A);

  struct Cholmod;
  std::unique_ptr<Cholmod> cholmod_;
  LaggedCholeskySettings settings_;
  bool valid_ = false, exact_ = false;
  int factorizations_ = 0, applications_since_ = 0;
  double refresh_cost_ = 0.0;  // CG iterations that cost about one factorisation
  PatternMemo pattern_;  // the pattern the factorisation was analysed for
};

}  // namespace sinew
