#pragma once
// Sparse Cholesky factorisation P M P^T = L L^T of a symmetric positive definite matrix with 3
// DOFs per vertex, on 3x3 vertex blocks: the ordering (AMD) and L's block pattern come from the
// vertex graph, and each update is a fixed-size 3x3 product. For the small meshes of paper 001's
// scenes (56 and 27 hexahedra, a factorisation per SQP iteration) Eigen's simplicial LLT spent its
// time in scalar, indirectly addressed updates and in permuting M into a new matrix at every
// factorisation, CHOLMOD its supernodal one in fixed costs. Here the positions of M's lower
// triangle among L's blocks are found once (analyze), so a factorisation reads M's values
// directly into L.
#include <Eigen/Core>
#include <Eigen/Sparse>
#include <cstdint>
#include <vector>

#include "sinew/core/types.hpp"

namespace sinew {

class BlockCholesky {
 public:
  // Whether M suits the block factorisation: 3 DOFs per vertex and its vertex blocks at least
  // half filled (else the scalar factorisations do less work).
  static bool suits(const Eigen::SparseMatrix<double>& M);

  // The ordering, L's block pattern and where M's entries go (M compressed).
  void analyze(const Eigen::SparseMatrix<double>& M);
  // Factorises M (its lower triangle read; analysed again if its pattern is not the analysed
  // one); false if M is not positive definite. `pattern`: the caller's id of M's sparsity
  // pattern, which it changes whenever the pattern changes (0: none); M's pattern is compared with
  // the analysed one only when the id is 0 or not the one it was last found equal under.
  bool factorize(const Eigen::SparseMatrix<double>& M, std::uint64_t pattern = 0);

  // x = M^-1 b.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
  // J M^-1 J^T = Z^T Z with Z = L^-1 P J^T: forward substitutions only, each starting at the
  // first block its sparse right-hand side touches.
  Eigen::MatrixXd gram(const Eigen::SparseMatrix<double, Eigen::RowMajor>& J) const;

  // Counts of the equivalent scalar factor (for cost estimates): sum of squared column counts
  // (the factorisation's flops, as CHOLMOD counts them) and nonzeros of L.
  double flops() const { return flops_; }
  double nonzeros() const { return lnz_; }

 private:
  bool same_pattern(const Eigen::SparseMatrix<double>& M) const;

  int vertices_ = 0;
  std::vector<int> new_of_old_, old_of_new_;  // vertex ordering
  // L by block columns (permuted order): column j's blocks are [start_[j], start_[j + 1]), the
  // first its diagonal block, rows_ ascending.
  std::vector<int> start_, rows_;
  // The blocks, each 3x3 padded to 4 rows (src/solver/block_cholesky_kernels.hpp), and the
  // inverse of each column's 3x3 Cholesky factor, likewise.
  std::vector<double> blocks_, diagonal_inverse_;
  std::vector<int> work_;  // the factorisation's lists, 4 ints per vertex
  // For each block entry (b, i, j) of L's pattern that M fills: M's value index (its lower
  // triangle in M's own numbering), and the entry's index 12 b + i + 4 j among blocks_' doubles.
  std::vector<int> source_, target_;
  std::vector<int> pattern_outer_, pattern_inner_;  // M's analysed pattern
  std::uint64_t pattern_id_ = 0;                    // the caller's id of it (0: none)
  double flops_ = 0.0, lnz_ = 0.0;
};

}  // namespace sinew
