#pragma once
// The Newton system's matrix as an operator, so Newton never depends on how it is stored:
// today an assembled sparse matrix; a matrix-free, multigrid or GPU backend implements the
// same interface (apply, block diagonal) and plugs in without touching the Newton loop.
#include <Eigen/Sparse>
#include <cstdint>

#include "sinew/core/types.hpp"
#include "sinew/linalg/element_matrices.hpp"

namespace sinew {

class LinearOperator {
 public:
  virtual ~LinearOperator() = default;
  virtual Eigen::Index rows() const = 0;
  // y = A x
  virtual void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const = 0;
  // The 3x3 diagonal block of vertex v (for Jacobi-type preconditioners).
  virtual Mat3 diagonal_block(Eigen::Index v) const = 0;
  // The assembled matrix when there is one (direct solvers need it), else nullptr.
  virtual const Eigen::SparseMatrix<double>* matrix() const { return nullptr; }
  // An id that changes whenever matrix()'s sparsity pattern may have changed, so that
  // preconditioners can reuse symbolic work without keeping and comparing the pattern; 0 when
  // unknown (then they compare).
  virtual std::uint64_t pattern_id() const { return 0; }
  // A matrix-free operator as a sum of element matrices (its Dirichlet identity rows left out),
  // for preconditioners that need more than products; nullptr when it has none.
  virtual const ElementMatrices* element_matrices() const { return nullptr; }
};

// A view of an assembled symmetric sparse matrix (not owning it).
class SparseOperator final : public LinearOperator {
 public:
  explicit SparseOperator(const Eigen::SparseMatrix<double>& A) : A_(&A) {}
  Eigen::Index rows() const override { return A_->rows(); }
  // Parallel over columns (oneTBB): for a symmetric matrix, column c dotted with x is row c of
  // A x, so each output entry is written by one task, with a fixed summation order.
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override;
  Mat3 diagonal_block(Eigen::Index v) const override;
  const Eigen::SparseMatrix<double>* matrix() const override { return A_; }

 private:
  const Eigen::SparseMatrix<double>* A_;
};

}  // namespace sinew
