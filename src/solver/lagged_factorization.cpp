#include "sinew/solver/lagged_factorization.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>

#include "sinew/core/error.hpp"
#include "sinew/linalg/linear_operator.hpp"
#include "sinew/solver/block_cholesky.hpp"

namespace sinew {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Eigen's simplicial factorisation works column by column, CHOLMOD's supernodal one on dense
// blocks of columns with the same pattern. Below ~40 entries per column of L (AMD ordering) the
// supernodes are too small for the dense kernels to pay for CHOLMOD's fixed costs; above, they
// win: measured on hexahedral lattices (3 DOFs per vertex), the 14 x 2 x 2 cells of paper 001's
// beam (405 DOFs, 34 entries per column) factorise in 0.29 ms simplicial against 0.54 ms with
// CHOLMOD, the 3 x 3 x 3 sphere (192 DOFs, 41) in the same time, and 5 x 5 x 5 cells (648 DOFs,
// 86) in 2.4 ms against 1.0 ms; CHOLMOD's solves are faster throughout.
constexpr double kSimplicialMeanColumn = 36.0;

bool short_columns(const Eigen::SparseMatrix<double>& M) {
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> trial;
  trial.compute(M);
  return trial.info() == Eigen::Success &&
         static_cast<double>(trial.matrixL().nestedExpression().nonZeros()) <= kSimplicialMeanColumn * M.rows();
}

// y = M x for the symmetric stepper matrices in compressed column storage (column c dotted with
// x is row c of M x), serial: CG's products on the small matrices this class mostly sees are a
// few microseconds. Where a vertex's three columns have the same rows (the stepper's matrices
// are assembled from full 3x3 blocks) they are done together, each x entry read once for three
// running sums; otherwise a column at a time with four partial sums, which break the chain of
// dependent additions a single running sum makes. Fixed order: deterministic.
bool same_rows(const int* outer, const int* inner, Eigen::Index c) {
  const int length = outer[c + 1] - outer[c];
  return outer[c + 2] - outer[c + 1] == length && outer[c + 3] - outer[c + 2] == length &&
         std::equal(inner + outer[c], inner + outer[c + 1], inner + outer[c + 1]) &&
         std::equal(inner + outer[c], inner + outer[c + 1], inner + outer[c + 2]);
}

void symmetric_product_serial(const Eigen::SparseMatrix<double>& M, const std::vector<char>& vertex_columns,
                              const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  const int* outer = M.outerIndexPtr();
  const int* inner = M.innerIndexPtr();
  const double* values = M.valuePtr();
  const double* xs = x.data();
  y.resize(M.rows());
  for (Eigen::Index c = 0; c < M.outerSize();) {
    if (vertex_columns[static_cast<size_t>(c)]) {
      const int begin = outer[c], length = outer[c + 1] - begin;
      const double* v0 = values + begin;
      const double* v1 = values + outer[c + 1];
      const double* v2 = values + outer[c + 2];
      const int* rows = inner + begin;
      double s0 = 0.0, s1 = 0.0, s2 = 0.0;
      for (int k = 0; k < length; ++k) {
        const double xr = xs[rows[k]];
        s0 += v0[k] * xr;
        s1 += v1[k] * xr;
        s2 += v2[k] * xr;
      }
      y[c] = s0;
      y[c + 1] = s1;
      y[c + 2] = s2;
      c += 3;
      continue;
    }
    const int begin = outer[c], end = outer[c + 1];
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    int k = begin;
    for (; k + 4 <= end; k += 4) {
      s0 += values[k] * xs[inner[k]];
      s1 += values[k + 1] * xs[inner[k + 1]];
      s2 += values[k + 2] * xs[inner[k + 2]];
      s3 += values[k + 3] * xs[inner[k + 3]];
    }
    for (; k < end; ++k) s0 += values[k] * xs[inner[k]];
    y[c] = (s0 + s1) + (s2 + s3);
    ++c;
  }
}

// Per column: 1 where it starts a triple of columns (3 v, 3 v + 1, 3 v + 2) with the same rows.
std::vector<char> vertex_column_starts(const Eigen::SparseMatrix<double>& M) {
  std::vector<char> starts(static_cast<size_t>(M.outerSize()), 0);
  if (M.outerSize() % 3 != 0) return starts;
  for (Eigen::Index c = 0; c + 2 < M.outerSize(); c += 3)
    starts[static_cast<size_t>(c)] = same_rows(M.outerIndexPtr(), M.innerIndexPtr(), c) ? 1 : 0;
  return starts;
}

}  // namespace

struct LaggedFactorization::Backends {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> cholmod;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> simplicial;
  BlockCholesky block;
};

LaggedFactorization::LaggedFactorization() : backends_(std::make_unique<Backends>()) {}
LaggedFactorization::~LaggedFactorization() = default;

void LaggedFactorization::use(const Eigen::SparseMatrix<double>& M, const FactorizationReuse& reuse,
                              Counters& counters, std::uint64_t pattern) {
  current_ = &M;
  pattern_ = pattern;
  reuse_ = reuse;
  exact_ = false;
  if (!reuse.enabled || !valid_ || cg_iterations_since_ >= cg_iterations_per_factorization_) refactor(counters);
}

void LaggedFactorization::refactor(Counters& counters) {
  const auto t = Clock::now();
  if (!analysed_) {
    backend_ = Backend::Cholmod;
    if (current_->rows() < reuse_.block_factorization_below)
      backend_ = BlockCholesky::suits(*current_) ? Backend::Block
                 : short_columns(*current_)      ? Backend::Simplicial
                                                 : Backend::Cholmod;
  }
  // Factorises with the pattern analysed once; again after a new analysis if that fails (the
  // pattern can change when the warped stiffness cancels entries).
  auto factorize = [&](auto& llt) {
    if (!analysed_) llt.analyzePattern(*current_);
    llt.factorize(*current_);
    if (llt.info() != Eigen::Success) {
      llt.analyzePattern(*current_);
      llt.factorize(*current_);
    }
    return llt.info() == Eigen::Success;
  };
  switch (backend_) {
    case Backend::Block:
      if (!analysed_) backends_->block.analyze(*current_);
      valid_ = backends_->block.factorize(*current_, pattern_);
      break;
    case Backend::Simplicial:
      valid_ = factorize(backends_->simplicial);
      break;
    case Backend::Cholmod:
      valid_ = factorize(backends_->cholmod);
      break;
  }
  analysed_ = true;
  if (!valid_) throw Error("backward-Euler or SQP matrix is not positive definite", "constrained stepper");
  // Flops of a factorisation and nonzeros of L: CHOLMOD counts them; for the simplicial factor,
  // sum_j c_j^2 over its column counts c_j (the same count CHOLMOD makes), likewise the block one.
  double flops = 0.0, lnz = 0.0;
  if (backend_ == Backend::Simplicial) {
    const auto& L = backends_->simplicial.matrixL().nestedExpression();
    for (Eigen::Index j = 0; j < L.outerSize(); ++j) {
      const double c = static_cast<double>(L.outerIndexPtr()[j + 1] - L.outerIndexPtr()[j]);
      flops += c * c;
    }
    lnz = static_cast<double>(L.nonZeros());
  } else if (backend_ == Backend::Block) {
    flops = backends_->block.flops();
    lnz = backends_->block.nonzeros();
  } else {
    const cholmod_common& c = backends_->cholmod.cholmod();
    flops = c.fl;
    lnz = c.lnz;
  }
  cg_iterations_per_factorization_ = flops / (4.0 * lnz + 2.0 * static_cast<double>(current_->nonZeros()));
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
    out = precondition(r);
  }
  counters.solve_seconds += since(t) - (counters.factor_seconds - factor_seconds_before);
}

bool LaggedFactorization::preconditioned_cg(const Eigen::VectorXd& r, Eigen::VectorXd& out, bool guess,
                                            Counters& counters) {
  const Eigen::Index n = r.size();
  const double r_norm = r.norm();
  if (!guess || r_norm == 0.0) out.setZero(n);
  if (r_norm == 0.0) return true;
  const double target = reuse_.cg_tolerance * r_norm;
  // Below block_factorization_below rows (the matrices the small factorisations serve) the product runs
  // serially with four partial sums; larger ones use the parallel SparseOperator.
  const SparseOperator op(*current_);
  const bool small = current_->rows() < reuse_.block_factorization_below && current_->isCompressed();
  if (small && !product_pattern_.same_or_remember(*current_, pattern_)) vertex_columns_ = vertex_column_starts(*current_);
  auto apply = [&](const Eigen::VectorXd& p, Eigen::VectorXd& y) {
    if (small)
      symmetric_product_serial(*current_, vertex_columns_, p, y);
    else
      op.apply(p, y);
  };
  Eigen::VectorXd res = r, Ap(n);
  if (guess) {
    apply(out, Ap);
    res -= Ap;
  }
  if (res.norm() <= target) return true;
  Eigen::VectorXd z = precondition(res), p = z;
  double rz = res.dot(z);
  for (int it = 0; it < reuse_.max_cg_iterations; ++it) {
    apply(p, Ap);
    const double alpha = rz / p.dot(Ap);
    out += alpha * p;
    res -= alpha * Ap;
    ++counters.cg_iterations;
    ++cg_iterations_since_;
    if (res.norm() <= target) return true;
    z = precondition(res);
    const double rz_next = res.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  return false;
}

Eigen::VectorXd LaggedFactorization::precondition(const Eigen::VectorXd& r) const {
  switch (backend_) {
    case Backend::Block: return backends_->block.solve(r);
    case Backend::Simplicial: return backends_->simplicial.solve(r);
    case Backend::Cholmod: break;
  }
  return backends_->cholmod.solve(r);
}

Eigen::MatrixXd LaggedFactorization::apply_inverse(const Eigen::MatrixXd& B) const {
  switch (backend_) {
    case Backend::Block: return backends_->block.solve(B);
    case Backend::Simplicial: return backends_->simplicial.solve(B);
    case Backend::Cholmod: break;
  }
  return backends_->cholmod.solve(B);
}

Eigen::MatrixXd LaggedFactorization::gram(const Eigen::SparseMatrix<double, Eigen::RowMajor>& J) const {
  const Eigen::Index m = J.rows();
  if (backend_ == Backend::Block) return backends_->block.gram(J);
  Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(J.cols(), m);
  if (backend_ == Backend::Simplicial) {
    // Eigen's simplicial factor: P = Perm^-1 L L^T Perm; row r of J^T lands in row Perm(r).
    const auto& llt = backends_->simplicial;
    const auto& perm = llt.permutationP().indices();
    for (Eigen::Index i = 0; i < m; ++i)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(J, i); it; ++it) Z(perm(it.col()), i) = it.value();
    llt.matrixL().solveInPlace(Z);
    Eigen::MatrixXd W(m, m);
    W.setZero();
    W.selfadjointView<Eigen::Lower>().rankUpdate(Z.transpose());
    return W.selfadjointView<Eigen::Lower>();
  }
  // CHOLMOD's supernodal factor: the full solve, then J times the columns.
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(J, i); it; ++it) Z(it.col(), i) = it.value();
  return J * apply_inverse(Z);
}

}  // namespace sinew
