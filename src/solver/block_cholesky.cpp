#include "sinew/solver/block_cholesky.hpp"

#include <Eigen/OrderingMethods>
#include <algorithm>

#include "block_cholesky_kernels.hpp"
#include "sinew/core/error.hpp"

namespace sinew {

bool BlockCholesky::suits(const Eigen::SparseMatrix<double>& M) {
  if (M.rows() != M.cols() || M.rows() % 3 != 0 || M.rows() == 0) return false;
  std::vector<Eigen::Triplet<double>> couplings;
  couplings.reserve(static_cast<size_t>(M.nonZeros()));
  for (Eigen::Index c = 0; c < M.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(M, c); it; ++it)
      couplings.emplace_back(static_cast<int>(it.row() / 3), static_cast<int>(c / 3), 1.0);
  Eigen::SparseMatrix<double> G(M.rows() / 3, M.cols() / 3);
  G.setFromTriplets(couplings.begin(), couplings.end());
  return 2 * M.nonZeros() >= 9 * G.nonZeros();
}

void BlockCholesky::analyze(const Eigen::SparseMatrix<double>& M) {
  if (M.rows() % 3 != 0 || M.rows() != M.cols() || !M.isCompressed())
    throw Error("needs a compressed square matrix with 3 DOFs per vertex", "block Cholesky");
  vertices_ = static_cast<int>(M.rows() / 3);
  pattern_id_ = 0;  // factorize() sets the caller's id of this pattern
  const int nv = vertices_;
  // The vertex graph and its fill-reducing ordering (as Eigen's simplicial factor: P = Pinv^-1).
  std::vector<Eigen::Triplet<double>> couplings;
  for (Eigen::Index c = 0; c < M.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(M, c); it; ++it)
      couplings.emplace_back(static_cast<int>(it.row() / 3), static_cast<int>(c / 3), 1.0);
  for (int v = 0; v < nv; ++v) couplings.emplace_back(v, v, 1.0);
  Eigen::SparseMatrix<double> G(nv, nv);
  G.setFromTriplets(couplings.begin(), couplings.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> Pinv;
  Eigen::AMDOrdering<int>()(G, Pinv);
  old_of_new_.assign(Pinv.indices().data(), Pinv.indices().data() + nv);
  new_of_old_.assign(static_cast<size_t>(nv), 0);
  for (int k = 0; k < nv; ++k) new_of_old_[static_cast<size_t>(old_of_new_[static_cast<size_t>(k)])] = k;

  // L's block pattern: column j holds j, M's rows below j, and its elimination-tree children's
  // rows below j.
  std::vector<std::vector<int>> below(static_cast<size_t>(nv)), children(static_cast<size_t>(nv));
  for (Eigen::Index c = 0; c < G.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(G, c); it; ++it) {
      const int a = new_of_old_[static_cast<size_t>(it.row())], b = new_of_old_[static_cast<size_t>(c)];
      if (a > b) below[static_cast<size_t>(b)].push_back(a);
    }
  start_.assign(1, 0);
  rows_.clear();
  flops_ = lnz_ = 0.0;
  for (int j = 0; j < nv; ++j) {
    std::vector<int>& s = below[static_cast<size_t>(j)];
    for (const int c : children[static_cast<size_t>(j)])
      for (int p = start_[static_cast<size_t>(c)] + 1; p < start_[static_cast<size_t>(c) + 1]; ++p)
        if (rows_[static_cast<size_t>(p)] > j) s.push_back(rows_[static_cast<size_t>(p)]);
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
    if (!s.empty()) children[static_cast<size_t>(s.front())].push_back(j);
    rows_.push_back(j);
    rows_.insert(rows_.end(), s.begin(), s.end());
    start_.push_back(static_cast<int>(rows_.size()));
    // The scalar columns of this block column hold 3 b, 3 b - 1 and 3 b - 2 entries.
    const double b = 1.0 + static_cast<double>(s.size());
    for (int i = 0; i < 3; ++i) {
      flops_ += (3.0 * b - i) * (3.0 * b - i);
      lnz_ += 3.0 * b - i;
    }
    std::vector<int>().swap(s);
  }
  blocks_.assign(rows_.size() * block_kernels::kBlock, 0.0);
  diagonal_inverse_.assign(static_cast<size_t>(nv) * block_kernels::kBlock, 0.0);
  work_.assign(4 * static_cast<size_t>(nv), 0);

  // Where M's lower triangle (in its own numbering, as Eigen's Lower reads it) goes among L's
  // blocks: entry (r, c), r >= c, of vertices (a, b) in the new order lands in block (a, b) at
  // (r mod 3, c mod 3) when a >= b, else in block (b, a) transposed (blocks padded to 4 rows).
  source_.clear();
  target_.clear();
  for (Eigen::Index c = 0; c < M.outerSize(); ++c)
    for (int k = M.outerIndexPtr()[c]; k < M.outerIndexPtr()[c + 1]; ++k) {
      const Eigen::Index r = M.innerIndexPtr()[k];
      if (r < c) continue;
      int a = new_of_old_[static_cast<size_t>(r / 3)], b = new_of_old_[static_cast<size_t>(c / 3)];
      int i = static_cast<int>(r % 3), j = static_cast<int>(c % 3);
      if (a < b) {
        std::swap(a, b);
        std::swap(i, j);
      }
      const auto first = rows_.begin() + start_[static_cast<size_t>(b)];
      const auto last = rows_.begin() + start_[static_cast<size_t>(b) + 1];
      const auto block = static_cast<int>(std::lower_bound(first, last, a) - rows_.begin());
      source_.push_back(k);
      target_.push_back(block_kernels::kBlock * block + i + 4 * j);
    }
  pattern_outer_.assign(M.outerIndexPtr(), M.outerIndexPtr() + M.outerSize() + 1);
  pattern_inner_.assign(M.innerIndexPtr(), M.innerIndexPtr() + M.nonZeros());
}

bool BlockCholesky::same_pattern(const Eigen::SparseMatrix<double>& M) const {
  return M.isCompressed() && static_cast<size_t>(M.outerSize() + 1) == pattern_outer_.size() &&
         static_cast<size_t>(M.nonZeros()) == pattern_inner_.size() &&
         std::equal(pattern_outer_.begin(), pattern_outer_.end(), M.outerIndexPtr()) &&
         std::equal(pattern_inner_.begin(), pattern_inner_.end(), M.innerIndexPtr());
}

bool BlockCholesky::factorize(const Eigen::SparseMatrix<double>& M, std::uint64_t pattern) {
  if (pattern == 0 || pattern != pattern_id_) {
    if (!same_pattern(M)) analyze(M);
    pattern_id_ = pattern;
  }
  std::fill(blocks_.begin(), blocks_.end(), 0.0);
  double* L = blocks_.data();
  const double* values = M.valuePtr();
  for (size_t k = 0; k < source_.size(); ++k) L[target_[k]] = values[source_[k]];
  return block_kernels::factorize(vertices_, start_.data(), rows_.data(), L, diagonal_inverse_.data(), work_.data());
}

Eigen::VectorXd BlockCholesky::solve(const Eigen::VectorXd& b) const {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(4 * vertices_);  // padded, permuted
  for (int v = 0; v < vertices_; ++v) y.segment<3>(4 * new_of_old_[static_cast<size_t>(v)]) = b.segment<3>(3 * v);
  block_kernels::forward(vertices_, start_.data(), rows_.data(), blocks_.data(), diagonal_inverse_.data(), y.data(), 0);
  block_kernels::backward(vertices_, start_.data(), rows_.data(), blocks_.data(), diagonal_inverse_.data(), y.data());
  Eigen::VectorXd x(b.size());
  for (int v = 0; v < vertices_; ++v) x.segment<3>(3 * v) = y.segment<3>(4 * new_of_old_[static_cast<size_t>(v)]);
  return x;
}

Eigen::MatrixXd BlockCholesky::solve(const Eigen::MatrixXd& B) const {
  // All right-hand sides at once, row-major (the kernels' layout: each block of L is read once
  // for all columns, the LCP's columns of H^-1 J^T, tens per solve), rows padded to whole
  // vectors.
  const int m = static_cast<int>(B.cols());
  const int ld = (m + 7) / 8 * 8;
  std::vector<double> Y(static_cast<size_t>(3 * vertices_) * static_cast<size_t>(ld), 0.0);
  for (int v = 0; v < vertices_; ++v) {
    double* y = Y.data() + static_cast<size_t>(3 * new_of_old_[static_cast<size_t>(v)]) * static_cast<size_t>(ld);
    for (int c = 0; c < m; ++c)
      for (int r = 0; r < 3; ++r) y[static_cast<size_t>(r * ld + c)] = B(3 * v + r, c);
  }
  block_kernels::forward_many(vertices_, start_.data(), rows_.data(), blocks_.data(), diagonal_inverse_.data(), Y.data(),
                              ld, m);
  block_kernels::backward_many(vertices_, start_.data(), rows_.data(), blocks_.data(), diagonal_inverse_.data(), Y.data(),
                               ld, m);
  Eigen::MatrixXd X(B.rows(), m);
  for (int v = 0; v < vertices_; ++v) {
    const double* y = Y.data() + static_cast<size_t>(3 * new_of_old_[static_cast<size_t>(v)]) * static_cast<size_t>(ld);
    for (int c = 0; c < m; ++c)
      for (int r = 0; r < 3; ++r) X(3 * v + r, c) = y[static_cast<size_t>(r * ld + c)];
  }
  return X;
}

Eigen::MatrixXd BlockCholesky::gram(const Eigen::SparseMatrix<double, Eigen::RowMajor>& J) const {
  const Eigen::Index m = J.rows();
  // Z padded like the kernels' vectors: its padding rows stay zero and add nothing to Z^T Z.
  Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(4 * vertices_, m);
  int first_of_all = vertices_;  // Z's rows above this vertex are zero in every column
  for (Eigen::Index i = 0; i < m; ++i) {
    int first = vertices_;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(J, i); it; ++it) {
      const int v = new_of_old_[static_cast<size_t>(it.col() / 3)];
      Z(4 * v + it.col() % 3, i) = it.value();
      first = std::min(first, v);
    }
    block_kernels::forward(vertices_, start_.data(), rows_.data(), blocks_.data(), diagonal_inverse_.data(),
                           Z.col(i).data(), first);
    first_of_all = std::min(first_of_all, first);
  }
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(m, m);
  // The rows every column has zero add nothing to Z^T Z: left out of the product.
  W.selfadjointView<Eigen::Lower>().rankUpdate(Z.bottomRows(4 * (vertices_ - first_of_all)).transpose());
  return W.selfadjointView<Eigen::Lower>();
}

}  // namespace sinew
