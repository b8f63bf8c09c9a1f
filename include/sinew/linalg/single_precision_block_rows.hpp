#pragma once
// A symmetric matrix whose pattern is made of full 3x3 vertex blocks (the Newton Hessian's),
// copied into single-precision block rows: one column index per block and its nine values side by
// side. A product streams 40 bytes per block, against 72 for a single-precision copy of the values
// that reads the compressed-column matrix's row indices (4 bytes per entry each). For operators
// that only precondition (the multigrid smoother): rounding to float changes a fixed linear
// operator, not the system CG solves.
#include <Eigen/Sparse>
#include <vector>

#include "sinew/linalg/linear_operator.hpp"

namespace sinew {

class SinglePrecisionBlockRows final : public LinearOperator {
 public:
  // Copies A (compressed, symmetric, both triangles stored); false, leaving the operator unusable,
  // if A's pattern is not made of full 3x3 blocks (each column 3v + k listing rows 3c, 3c + 1,
  // 3c + 2 of the same block columns c as columns 3v and 3v + 1). `original` answers
  // diagonal_block() and must outlive this operator's use.
  bool set(const Eigen::SparseMatrix<double>& A, const LinearOperator& original);

  Eigen::Index rows() const override { return 3 * (static_cast<Eigen::Index>(offsets_.size()) - 1); }
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override;
  Mat3 diagonal_block(Eigen::Index v) const override { return original_->diagonal_block(v); }
  std::size_t bytes() const;

 private:
  const LinearOperator* original_ = nullptr;
  std::vector<int> offsets_{0};  // block row r: blocks [offsets_[r], offsets_[r + 1])
  std::vector<int> columns_;     // per block
  std::vector<float> values_;    // 9 per block, row-major
};

}  // namespace sinew
