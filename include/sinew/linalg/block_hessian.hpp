#pragma once
// A sparse matrix of full 3x3 vertex blocks whose sparsity pattern is built once from the
// vertex couplings of every energy term and reused by every Newton iteration.
#include <Eigen/Sparse>
#include <cstdint>
#include <vector>

#include "sinew/core/types.hpp"
#include "sinew/linalg/linear_operator.hpp"

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

  // Where block (a, b) lives among matrix().valuePtr(): entry (i, j) of the block is at
  // block_offset(b, slot(a, b)) + i + j * column_stride(b). Element loops precompute the slots
  // once (a scatter map) instead of searching for every block of every element.
  Eigen::Index block_offset(int b, int k) const { return A_.outerIndexPtr()[3 * b] + 3 * k; }
  Eigen::Index column_stride(int b) const { return 3 * static_cast<Eigen::Index>(rows_[b].size()); }
  // Adds the 3x3 block M at (a, b) and its transpose at (b, a): one call per pair of distinct
  // nodes of a symmetric element matrix. `k_ab` = slot(a, b), `k_ba` = slot(b, a).
  void add_symmetric_pair(int a, int b, int k_ab, int k_ba, const Mat3& M);

  // Vertex b's three columns for element scatter loops that add many blocks to the same
  // vertices: where they start among the values and how far apart they are (block_offset,
  // column_stride read once). Slot k's block is at values + 3k.
  struct Columns {
    double* values;
    Eigen::Index stride;
    // Block at slot k += M, or += M^T.
    void add(int k, const Mat3& M) const {
      double* block = values + 3 * k;
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) block[i + j * stride] += M(i, j);
    }
    void add_transposed(int k, const Mat3& M) const {
      double* block = values + 3 * k;
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) block[i + j * stride] += M(j, i);
    }
    // Asks the cache for the block at slot k ahead of an add: scatter loops prefetch a later
    // element's blocks while the stiffness before it is computed, since on a large lattice most
    // blocks come from L3 or memory (their three column segments are a column stride apart).
    void prefetch(int k) const {
      const double* block = values + 3 * k;
      for (int j = 0; j < 3; ++j) {
        __builtin_prefetch(block + j * stride, 1, 3);
        __builtin_prefetch(block + j * stride + 2, 1, 3);
      }
    }
  };
  Columns columns(int b) {
    const auto* outer = A_.outerIndexPtr();
    return {A_.valuePtr() + outer[3 * b], outer[3 * b + 1] - outer[3 * b]};
  }
  // Changes with every pattern built (a new pattern gets a new id), so a cached scatter map can
  // tell whether it still matches.
  std::uint64_t pattern_id() const { return pattern_id_; }
  // The row vertices of column vertex b, sorted (slot(a, b) is a's position here).
  const std::vector<int>& column_vertices(int b) const { return rows_[static_cast<size_t>(b)]; }
  // The largest number of row vertices of any column vertex (the range of slot()).
  int max_slots() const;

  // Replaces the rows and columns of the DOFs flagged in `fixed` (one flag per DOF) by those of
  // the identity; the pattern is unchanged. Visits only the fixed DOFs' blocks.
  void set_identity_rows(const std::vector<char>& fixed);

  // y = A x for the symmetric A, in parallel with a fixed summation order.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  // The 3x3 diagonal block of vertex v, read at its slot (no search through the column).
  Mat3 diagonal_block(int v) const;

  // Expresses the DOFs of some vertices in rotated frames: block (a, b) becomes
  // Q_a^T A_ab Q_b, with `frames[v]` = Q_v (null: the identity). The pattern is unchanged.
  void change_basis(const std::vector<const Mat3*>& frames);

 private:
  Eigen::SparseMatrix<double> A_;
  std::vector<std::vector<int>> rows_;  // sorted row vertices of each column vertex
  std::uint64_t pattern_id_ = 0;
};

// A BlockHessian as the Newton system's operator (not owning it); matrix() for direct solvers
// and multigrid.
class BlockHessianOperator final : public LinearOperator {
 public:
  explicit BlockHessianOperator(const BlockHessian& H) : H_(&H) {}
  Eigen::Index rows() const override { return H_->matrix().rows(); }
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override { H_->multiply(x, y); }
  Mat3 diagonal_block(Eigen::Index v) const override { return H_->diagonal_block(static_cast<int>(v)); }
  const Eigen::SparseMatrix<double>* matrix() const override { return &H_->matrix(); }
  std::uint64_t pattern_id() const override { return H_->pattern_id(); }

 private:
  const BlockHessian* H_;
};

}  // namespace sinew
