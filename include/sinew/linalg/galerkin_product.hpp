#pragma once
// The Galerkin coarse operator C = P^T A P of a symmetric matrix of 3x3 vertex blocks, with P a
// VertexInterpolation restricted to the free DOFs (fixed fine DOFs are dropped; a coarse DOF
// left with no free fine DOF gets an identity row). The pattern of C and, per coarse vertex, the
// fine vertices it interpolates are found once (symbolic); each Newton matrix then costs one
// pass over C: row I is the sum of w_aI (A P)_a over those fine vertices a, in parallel over the
// rows (no races), each row's terms in a fixed order (a colouring of the fine vertices), so the
// sums are deterministic.
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
  int colors() const { return colors_; }

 private:
  template <class BlockRow>
  void compute_rows(const BlockRow& row, std::span<const char> fine_free, std::span<const char> coarse_free,
                    BlockSparseMatrix& C) const;

  const VertexInterpolation* P_ = nullptr;
  std::vector<std::vector<int>> coarse_pattern_;
  int colors_ = 0;  // of fine vertices sharing no coarse vertex: they order each row's terms
  // Per coarse vertex I, entries [gather_offsets_[I], gather_offsets_[I + 1]) of gather_entries_:
  // the interpolation entries k (fine vertex entry_fine_[k], weight P.weight[k]) with coarse
  // vertex I, by colour of their fine vertex.
  std::vector<int> gather_offsets_, gather_entries_, entry_fine_;
};

}  // namespace sinew
