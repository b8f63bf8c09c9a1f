#pragma once
// The Galerkin coarse operator C = P^T A P of a matrix given as element matrices
// (linalg/element_matrices.hpp), without assembling A: C = sum_e P_e^T K_e P_e, where P_e holds
// the interpolation rows of element e's vertices restricted to the free DOFs. The same product as
// GalerkinProduct (linalg/galerkin_product.hpp) computes from an assembled A, for matrix-free
// Newton systems whose fine matrix is never formed. The symbolic part (the pattern of C, and the
// elements grouped by their coarse vertices, the groups coloured so that no two groups of a colour
// share a coarse vertex) is built
// once per ElementMatrices::structure_id(); each numeric product is then one parallel pass over
// the elements without atomics, with a fixed summation order.
#include <cstdint>
#include <span>
#include <vector>

#include "sinew/linalg/block_sparse_matrix.hpp"
#include "sinew/linalg/element_matrices.hpp"
#include "sinew/linalg/vertex_interpolation.hpp"

namespace sinew {

class ElementGalerkin {
 public:
  ElementGalerkin() = default;
  // P must be prepared (transpose built) and interpolate to A's vertices.
  ElementGalerkin(const ElementMatrices& A, const VertexInterpolation& P);

  std::uint64_t structure_id() const { return structure_id_; }
  // A coarse matrix with C's pattern (values zero).
  BlockSparseMatrix make_coarse() const { return BlockSparseMatrix(coarse_pattern_); }
  // C = P^T A P over the free DOFs (a coarse DOF with no free fine DOF gets an identity row, as in
  // GalerkinProduct). `C` must come from make_coarse().
  void compute(const ElementMatrices& A, std::span<const char> fine_free, std::span<const char> coarse_free,
               BlockSparseMatrix& C) const;
  int colors() const { return static_cast<int>(colors_.size()); }

 private:
  const VertexInterpolation* P_ = nullptr;
  std::uint64_t structure_id_ = 0;
  std::vector<std::vector<int>> coarse_pattern_;
  // Groups of elements with the same coarse vertices (CSR: group g's elements are
  // group_elements_[group_offsets_[g] .. group_offsets_[g + 1])), by colour.
  std::vector<std::int64_t> group_offsets_;
  std::vector<Eigen::Index> group_elements_;
  std::vector<std::vector<int>> colors_;  // groups by colour
  std::vector<Eigen::Index> serial_;      // elements of the groups no colour was left for (done serially)
};

}  // namespace sinew
