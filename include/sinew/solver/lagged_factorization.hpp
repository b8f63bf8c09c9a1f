#pragma once
// A sparse Cholesky factorisation (CHOLMOD supernodal, or for small matrices a 3x3-block one or
// Eigen's simplicial LLT) of an earlier matrix, used for solves
// with the current one: directly while it is of the current matrix, else by CG preconditioned
// with it, which stays exact to the CG tolerance. It is refreshed when the CG work it has caused
// reaches the cost of a new factorisation (rent-or-buy; the costs come from CHOLMOD's own flop
// and nonzero counts, so the choice is deterministic), or when one solve needs more CG
// iterations than allowed. It also keeps, per constraint, the columns P^-1 J_i^T computed with
// it (the constrained stepper's LCP matrix), dropped when it is refreshed.
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "sinew/linalg/pattern_memo.hpp"

namespace sinew {

struct FactorizationReuse {
  bool enabled = true;
  // A lagged factorisation is refreshed at the start of a step once the CG iterations spent
  // since it was made cost about as much as a factorisation (estimated from CHOLMOD's flop and
  // nonzero counts, so the choice is deterministic), and in any step where one solve needs more
  // than `max_cg_iterations`.
  int max_cg_iterations = 12;
  double cg_tolerance = 1e-6;         // relative residual of the preconditioned CG solves
  int max_splitting_iterations = 30;  // LCP splitting sweeps before W is formed exactly
  // A column P^-1 J_i^T is kept while the factorisation lasts and reused while row i's Jacobian
  // stays within this relative distance of the one it was computed for (0: exact match only).
  double column_reuse_tolerance = 0.1;
  // Matrices with fewer rows than this are factorised on 3x3 vertex blocks (BlockCholesky) when
  // they have 3 DOFs per vertex and filled blocks, else by Eigen's simplicial LLT when their
  // factor has short columns (lagged_factorization.cpp), instead of CHOLMOD's supernodal one.
  // On paper 001's scenes CHOLMOD's fixed costs (permuting A into a new matrix, BLAS calls on
  // tiny supernodes) are most of a small factorisation, and its solves with the LCP's tens of
  // right-hand sides cost more than the block kernels' up to ~5,500 DOFs, where a step with
  // factorisation reuse is still 20-28 % faster on blocks though a block factorisation takes
  // 1.75x CHOLMOD's time; at ~11,000 DOFs (8x) CHOLMOD wins (docs/performance.md). All give
  // the same factor up to rounding; 0 always uses CHOLMOD.
  int block_factorization_below = 6000;
  // The constrained stepper factorises every Lagrangian Hessian (no lagged one) when a
  // factorisation costs fewer CG iterations than this (refresh_cost(): about 5 for paper 001's
  // beam, 8 for its 27-hexahedron sphere, 50 at 1,872 DOFs): a lagged H costs two or more CG
  // solves and the splitting per SQP iteration, more than factorising. 0: always lagged.
  double exact_lagrangian_below = 12.0;
};

class LaggedFactorization {
 public:
  struct Column {
    std::vector<std::pair<Eigen::Index, double>> jacobian;  // the row J~_i the column is for
    Eigen::VectorXd values;                                 // P^-1 J~_i^T
  };
  struct Counters {
    int factorizations = 0, cg_iterations = 0;
    double factor_seconds = 0.0, solve_seconds = 0.0;
  };

  LaggedFactorization();
  ~LaggedFactorization();

  // Makes M the current matrix (kept by pointer: it must outlive its use) and factorises it
  // when reuse is off, when there is no factorisation yet, or when the budget is spent. Every
  // matrix given here must have the same sparsity pattern (one symbolic analysis). `pattern`:
  // the caller's id of M's sparsity pattern, changed whenever the pattern changes (0: none);
  // under an id the pattern was already seen with, it is not compared again.
  void use(const Eigen::SparseMatrix<double>& M, const FactorizationReuse& reuse, Counters& counters,
           std::uint64_t pattern = 0);
  // Factorises the current matrix now.
  void refactor(Counters& counters);
  // Whether the factorisation is of the current matrix.
  bool exact() const { return exact_; }
  // out = M^-1 r for the current M: directly when exact, else by preconditioned CG from `out`
  // (when `guess`) or from zero; refactorises and solves directly when CG needs too long.
  void solve(const Eigen::VectorXd& r, Eigen::VectorXd& out, bool guess, Counters& counters);
  // P^-1 B with the factorisation at hand (one multi-right-hand-side solve).
  Eigen::MatrixXd apply_inverse(const Eigen::MatrixXd& B) const;
  // J P^-1 J^T with the factorisation at hand, without the columns P^-1 J^T: with P = L L^T
  // (permuted) it is Z^T Z for Z = L^-1 J^T, forward substitutions only, which skip the zeros of
  // the sparse right-hand sides. For the LCP matrix of a factorisation that is not kept.
  Eigen::MatrixXd gram(const Eigen::SparseMatrix<double, Eigen::RowMajor>& J) const;
  // CG iterations that cost about one factorisation: flops of the factorisation over those of a
  // CG iteration (a triangular solve pair, 4 nnz(L), and a product with M, 2 nnz(M)). Per flop
  // the factorisation's dense supernode updates run faster than the solves, but a refresh also
  // drops the cached columns; flops alone measured best (x1 against x0.5 and x3 on the
  // paper-size benchmark of docs/performance.md).
  double refresh_cost() const { return cg_iterations_per_factorization_; }
  std::unordered_map<long, Column>& columns() { return columns_; }

 private:
  // CG from `out` (or zero); false when it did not reach the tolerance within the budget.
  bool preconditioned_cg(const Eigen::VectorXd& r, Eigen::VectorXd& out, bool guess, Counters& counters);

  // z = P^-1 r with the factorisation at hand.
  Eigen::VectorXd precondition(const Eigen::VectorXd& r) const;

  struct Backends;
  std::unique_ptr<Backends> backends_;
  // Chosen with the symbolic analysis, from the matrix's size and structure.
  enum class Backend { Cholmod, Simplicial, Block };
  Backend backend_ = Backend::Cholmod;
  const Eigen::SparseMatrix<double>* current_ = nullptr;
  FactorizationReuse reuse_;
  bool analysed_ = false, valid_ = false, exact_ = false;
  double cg_iterations_per_factorization_ = 0.0;
  int cg_iterations_since_ = 0;
  std::unordered_map<long, Column> columns_;
  // The pattern CG's serial product was last prepared for, and its columns that start a vertex's
  // triple of columns with equal rows (lagged_factorization.cpp).
  PatternMemo product_pattern_;
  std::vector<char> vertex_columns_;
  std::uint64_t pattern_ = 0;  // the current matrix's pattern id (0: none)
};

}  // namespace sinew
