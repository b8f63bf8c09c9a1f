#pragma once
// A symmetric matrix stored as rows of 3x3 vertex blocks (block CSR, both triangles): the coarse
// operators of multigrid. Its pattern is set once; Newton iterations overwrite the values. The
// product runs in parallel over block rows, each output block written by one task.
#include <Eigen/Sparse>
#include <vector>

#include "sinew/core/types.hpp"
#include "sinew/linalg/linear_operator.hpp"

namespace sinew {

class BlockSparseMatrix final : public LinearOperator {
 public:
  BlockSparseMatrix() = default;
  // `columns[r]`: the block columns of block row r, sorted and without repeats.
  explicit BlockSparseMatrix(const std::vector<std::vector<int>>& columns);

  Eigen::Index block_rows() const { return static_cast<Eigen::Index>(offsets_.size()) - 1; }
  Eigen::Index rows() const override { return 3 * block_rows(); }
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override;
  Mat3 diagonal_block(Eigen::Index v) const override;

  void set_zero();
  // Position of block (r, c) in blocks(); -1 if outside the pattern.
  int slot(int r, int c) const;
  // Block row r: columns [column_begin(r), column_end(r)) with their blocks at the same positions.
  int row_begin(int r) const { return offsets_[static_cast<size_t>(r)]; }
  int row_end(int r) const { return offsets_[static_cast<size_t>(r) + 1]; }
  int column(int k) const { return columns_[static_cast<size_t>(k)]; }
  Mat3& block(int k) { return blocks_[static_cast<size_t>(k)]; }
  const Mat3& block(int k) const { return blocks_[static_cast<size_t>(k)]; }
  Eigen::Index num_blocks() const { return static_cast<Eigen::Index>(blocks_.size()); }

  // The scalar lower triangle (for a Cholesky factorisation) as a compressed column matrix.
  Eigen::SparseMatrix<double> lower_triangle() const;

 private:
  std::vector<int> offsets_{0};
  std::vector<int> columns_;
  std::vector<Mat3, Eigen::aligned_allocator<Mat3>> blocks_;
};

}  // namespace sinew
