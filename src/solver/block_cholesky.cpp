#include "sinew/solver/block_cholesky.hpp"

#include <Eigen/Cholesky>
#include <Eigen/OrderingMethods>
#include <algorithm>

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
  blocks_.assign(rows_.size(), Mat3::Zero());
  diagonal_inverse_.assign(static_cast<size_t>(nv), Mat3::Identity());

  // Where M's lower triangle (in its own numbering, as Eigen's Lower reads it) goes among L's
  // blocks: entry (r, c), r >= c, of vertices (a, b) in the new order lands in block (a, b) at
  // (r mod 3, c mod 3) when a >= b, else in block (b, a) transposed.
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
      target_.push_back(9 * block + i + 3 * j);
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

bool BlockCholesky::factorize(const Eigen::SparseMatrix<double>& M) {
  if (!same_pattern(M)) analyze(M);
  std::fill(blocks_.begin(), blocks_.end(), Mat3::Zero());
  double* L = blocks_.data()->data();
  const double* values = M.valuePtr();
  for (size_t k = 0; k < source_.size(); ++k) L[target_[k]] = values[source_[k]];

  // Left-looking: column j gets the updates of every earlier column k with a block in row j
  // (k waits in the list of the row of its next unused block), then its own factor.
  const int nv = vertices_;
  std::vector<int> head(static_cast<size_t>(nv), -1), next(static_cast<size_t>(nv), -1),
      cursor(static_cast<size_t>(nv), 0), position(static_cast<size_t>(nv), -1);
  auto enqueue = [&](int k) {
    const int row = rows_[static_cast<size_t>(cursor[static_cast<size_t>(k)])];
    next[static_cast<size_t>(k)] = head[static_cast<size_t>(row)];
    head[static_cast<size_t>(row)] = k;
  };
  for (int j = 0; j < nv; ++j) {
    const int begin = start_[static_cast<size_t>(j)], end = start_[static_cast<size_t>(j) + 1];
    for (int p = begin; p < end; ++p) position[static_cast<size_t>(rows_[static_cast<size_t>(p)])] = p;
    for (int k = head[static_cast<size_t>(j)]; k != -1;) {
      const int k_next = next[static_cast<size_t>(k)];
      const int p = cursor[static_cast<size_t>(k)], k_end = start_[static_cast<size_t>(k) + 1];
      const Mat3 Ljk_t = blocks_[static_cast<size_t>(p)].transpose();
      for (int q = p; q < k_end; ++q)
        blocks_[static_cast<size_t>(position[static_cast<size_t>(rows_[static_cast<size_t>(q)])])].noalias() -=
            blocks_[static_cast<size_t>(q)] * Ljk_t;
      if (p + 1 < k_end) {
        cursor[static_cast<size_t>(k)] = p + 1;
        enqueue(k);
      }
      k = k_next;
    }
    const Eigen::LLT<Mat3> llt(blocks_[static_cast<size_t>(begin)]);  // reads the lower triangle
    if (llt.info() != Eigen::Success) return false;
    const Mat3 Ljj = llt.matrixL();
    const Mat3 inverse = Ljj.triangularView<Eigen::Lower>().solve(Mat3::Identity());
    blocks_[static_cast<size_t>(begin)] = Ljj;
    diagonal_inverse_[static_cast<size_t>(j)] = inverse;
    const Mat3 inverse_t = inverse.transpose();
    for (int p = begin + 1; p < end; ++p) blocks_[static_cast<size_t>(p)] = (blocks_[static_cast<size_t>(p)] * inverse_t).eval();
    if (begin + 1 < end) {
      cursor[static_cast<size_t>(j)] = begin + 1;
      enqueue(j);
    }
  }
  return true;
}

void BlockCholesky::forward(Eigen::Ref<Eigen::VectorXd> y, int first_block) const {
  for (int j = first_block; j < vertices_; ++j) {
    auto yj = y.segment<3>(3 * j);
    if (yj.isZero(0.0)) continue;  // sparse right-hand sides: nothing to carry down
    const Vec3 z = diagonal_inverse_[static_cast<size_t>(j)] * yj;
    yj = z;
    for (int p = start_[static_cast<size_t>(j)] + 1; p < start_[static_cast<size_t>(j) + 1]; ++p)
      y.segment<3>(3 * rows_[static_cast<size_t>(p)]).noalias() -= blocks_[static_cast<size_t>(p)] * z;
  }
}

void BlockCholesky::backward(Eigen::Ref<Eigen::VectorXd> y) const {
  for (int j = vertices_ - 1; j >= 0; --j) {
    Vec3 s = y.segment<3>(3 * j);
    for (int p = start_[static_cast<size_t>(j)] + 1; p < start_[static_cast<size_t>(j) + 1]; ++p)
      s.noalias() -= blocks_[static_cast<size_t>(p)].transpose() * y.segment<3>(3 * rows_[static_cast<size_t>(p)]);
    y.segment<3>(3 * j).noalias() = diagonal_inverse_[static_cast<size_t>(j)].transpose() * s;
  }
}

Eigen::VectorXd BlockCholesky::solve(const Eigen::VectorXd& b) const {
  Eigen::VectorXd y(b.size());
  for (int v = 0; v < vertices_; ++v) y.segment<3>(3 * new_of_old_[static_cast<size_t>(v)]) = b.segment<3>(3 * v);
  forward(y, 0);
  backward(y);
  Eigen::VectorXd x(b.size());
  for (int v = 0; v < vertices_; ++v) x.segment<3>(3 * v) = y.segment<3>(3 * new_of_old_[static_cast<size_t>(v)]);
  return x;
}

Eigen::MatrixXd BlockCholesky::solve(const Eigen::MatrixXd& B) const {
  // All right-hand sides at once, row-major so that a vertex's 3 rows are contiguous: each block
  // of L is read once for all columns (the LCP's columns of H^-1 J^T, tens per solve).
  using Rows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  using Block = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::Index m = B.cols();
  Rows Y(B.rows(), m);
  for (int v = 0; v < vertices_; ++v) Y.middleRows<3>(3 * new_of_old_[static_cast<size_t>(v)]) = B.middleRows<3>(3 * v);
  Block z(3, m);
  for (int j = 0; j < vertices_; ++j) {
    auto yj = Y.middleRows<3>(3 * j);
    if (yj.isZero(0.0)) continue;  // sparse right-hand sides: nothing to carry down
    z.noalias() = diagonal_inverse_[static_cast<size_t>(j)] * yj;
    yj = z;
    for (int p = start_[static_cast<size_t>(j)] + 1; p < start_[static_cast<size_t>(j) + 1]; ++p)
      Y.middleRows<3>(3 * rows_[static_cast<size_t>(p)]).noalias() -= blocks_[static_cast<size_t>(p)] * z;
  }
  for (int j = vertices_ - 1; j >= 0; --j) {
    z = Y.middleRows<3>(3 * j);
    for (int p = start_[static_cast<size_t>(j)] + 1; p < start_[static_cast<size_t>(j) + 1]; ++p)
      z.noalias() -= blocks_[static_cast<size_t>(p)].transpose() * Y.middleRows<3>(3 * rows_[static_cast<size_t>(p)]);
    Y.middleRows<3>(3 * j).noalias() = diagonal_inverse_[static_cast<size_t>(j)].transpose() * z;
  }
  Eigen::MatrixXd X(B.rows(), m);
  for (int v = 0; v < vertices_; ++v) X.middleRows<3>(3 * v) = Y.middleRows<3>(3 * new_of_old_[static_cast<size_t>(v)]);
  return X;
}

Eigen::MatrixXd BlockCholesky::gram(const Eigen::SparseMatrix<double, Eigen::RowMajor>& J) const {
  const Eigen::Index m = J.rows();
  Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(J.cols(), m);
  for (Eigen::Index i = 0; i < m; ++i) {
    int first = vertices_;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(J, i); it; ++it) {
      const int v = new_of_old_[static_cast<size_t>(it.col() / 3)];
      Z(3 * v + it.col() % 3, i) = it.value();
      first = std::min(first, v);
    }
    forward(Z.col(i), first);
  }
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(m, m);
  W.selfadjointView<Eigen::Lower>().rankUpdate(Z.transpose());
  return W.selfadjointView<Eigen::Lower>();
}

}  // namespace sinew
