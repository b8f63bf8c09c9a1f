#pragma once
// The Galerkin coarse operator C = P^T A P of a symmetric matrix of 3x3 vertex blocks, with P a
// VertexInterpolation restricted to the free DOFs (fixed fine DOFs are dropped; a coarse DOF
// left with no free fine DOF gets an identity row). The pattern of C and a colouring of the fine
// vertices are found once (symbolic); each Newton matrix then costs one pass over A: per fine
// vertex a, the row (A P)_a is formed once and scattered into the rows of C that a interpolates,
// in parallel over the vertices of one colour (no two of them share a coarse vertex), so there
// are no races and the sums are deterministic.
#include <Eigen/Sparse>
#include <span>
#include <vector>

#include "sinew/linalg/block_sparse_matrix.hpp"
#include "sinew/linalg/vertex_interpolation.hpp"

namespace sinew {

// The block pattern of a matrix of 3x3 vertex blocks stored by columns: per vertex, the sorted
// vertices of its non-zero blocks.
std::vector<std::vector<int>> block_pattern(const Eigen::SparseMatrix<double>& A);
std::vector<std::vector<int>> block_pattern(const BlockSparseMatrix& A);

class GalerkinProduct {
 public:
  GalerkinProduct() = default;
  // `fine_pattern`: block pattern of A (block_pattern); P must be prepared (transpose built).
  GalerkinProduct(const std::vector<std::vector<int>>& fine_pattern, const VertexInterpolation& P);

  // A coarse matrix with C's pattern (values zero).
  BlockSparseMatrix make_coarse() const { return BlockSparseMatrix(coarse_pattern_); }
  // C = P^T A P over the free DOFs; `C` must come from make_coarse(). `fine_free` has one flag
  // per fine DOF, `coarse_free` per coarse DOF (VertexInterpolation::coarse_free).
  void compute(const Eigen::SparseMatrix<double>& A, std::span<const char> fine_free, std::span<const char> coarse_free,
               BlockSparseMatrix& C) const;
  void compute(const BlockSparseMatrix& A, std::span<const char> fine_free, std::span<const char> coarse_free,
               BlockSparseMatrix& C) const;
  int colors() const { return static_cast<int>(colors_.size()); }

 private:
  template <class BlockRow>
  void compute_rows(const BlockRow& row, std::span<const char> fine_free, std::span<const char> coarse_free,
                    BlockSparseMatrix& C) const;

  const VertexInterpolation* P_ = nullptr;
  std::vector<std::vector<int>> coarse_pattern_;
  std::vector<std::vector<int>> colors_;  // fine vertices by colour
};

}  // namespace sinew
