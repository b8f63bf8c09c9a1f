#pragma once
// A sparse matrix of full 3x3 vertex blocks whose sparsity pattern is built once from the
// vertex couplings of every energy term and reused by every Newton iteration.
#include <Eigen/Sparse>
#include <vector>

#include "sinew/core/types.hpp"

namespace sinew {

class BlockHessian {
 public:
  // `cliques`: groups of vertices that are all coupled to each other (e.g. an element's nodes).
  BlockHessian(Eigen::Index num_vertices, const std::vector<std::vector<int>>& cliques);

  Eigen::SparseMatrix<double>& matrix() { return A_; }
  const Eigen::SparseMatrix<double>& matrix() const { return A_; }
  void set_zero();

  // Index of row-vertex a among the rows of column-vertex b; -1 if the block is not in the
  // pattern.
  int slot(int a, int b) const;
  // A(rows of a, cols of b) += M, for k = slot(a, b). Not thread-safe for the same (a, b).
  void add_block_at_slot(int b, int k, const Mat3& M);
  // Same, looking the slot up; throws if (a, b) is outside the pattern.
  void add_block(int a, int b, const Mat3& M);

  // Expresses the DOFs of some vertices in rotated frames: block (a, b) becomes
  // Q_a^T A_ab Q_b, with `frames[v]` = Q_v (null: the identity). The pattern is unchanged.
  void change_basis(const std::vector<const Mat3*>& frames);

 private:
  Eigen::SparseMatrix<double> A_;
  std::vector<std::vector<int>> rows_;  // sorted row vertices of each column vertex
};

}  // namespace sinew
