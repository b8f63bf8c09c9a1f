#include "sinew/linalg/block_sparse_matrix.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace sinew {

BlockSparseMatrix::BlockSparseMatrix(const std::vector<std::vector<int>>& columns) {
  offsets_.assign(columns.size() + 1, 0);
  for (size_t r = 0; r < columns.size(); ++r) offsets_[r + 1] = offsets_[r] + static_cast<int>(columns[r].size());
  columns_.reserve(static_cast<size_t>(offsets_.back()));
  for (const auto& row : columns) columns_.insert(columns_.end(), row.begin(), row.end());
  blocks_.assign(columns_.size(), Mat3::Zero());
}

void BlockSparseMatrix::set_zero() {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks_.size(), 4096), [&](const auto& range) {
    for (size_t k = range.begin(); k != range.end(); ++k) blocks_[k].setZero();
  });
}

int BlockSparseMatrix::slot(int r, int c) const {
  const auto begin = columns_.begin() + row_begin(r), end = columns_.begin() + row_end(r);
  const auto it = std::lower_bound(begin, end, c);
  return it != end && *it == c ? static_cast<int>(it - columns_.begin()) : -1;
}

void BlockSparseMatrix::apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const Eigen::Index n = block_rows();
  y.resize(3 * n);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, n, 256), [&](const auto& range) {
    for (Eigen::Index r = range.begin(); r != range.end(); ++r) {
      Vec3 sum = Vec3::Zero();
      for (int k = row_begin(static_cast<int>(r)); k < row_end(static_cast<int>(r)); ++k)
        sum.noalias() += blocks_[static_cast<size_t>(k)] * x.segment<3>(3 * columns_[static_cast<size_t>(k)]);
      y.segment<3>(3 * r) = sum;
    }
  });
}

Mat3 BlockSparseMatrix::diagonal_block(Eigen::Index v) const {
  const int k = slot(static_cast<int>(v), static_cast<int>(v));
  return k < 0 ? Mat3::Zero() : blocks_[static_cast<size_t>(k)];
}

Eigen::SparseMatrix<double> BlockSparseMatrix::lower_triangle() const {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(blocks_.size() * 6);
  for (int r = 0; r < static_cast<int>(block_rows()); ++r)
    for (int k = row_begin(r); k < row_end(r); ++k) {
      const int c = column(k);
      if (c > r) continue;
      const Mat3& B = block(k);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          if (3 * r + i >= 3 * c + j) entries.emplace_back(3 * r + i, 3 * c + j, B(i, j));
    }
  Eigen::SparseMatrix<double> L(rows(), rows());
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

}  // namespace sinew
