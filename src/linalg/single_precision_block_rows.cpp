#include "sinew/linalg/single_precision_block_rows.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>

namespace sinew {

bool SinglePrecisionBlockRows::set(const Eigen::SparseMatrix<double>& A, const LinearOperator& original) {
  original_ = &original;
  offsets_.assign(1, 0);
  columns_.clear();
  values_.clear();
  if (!A.isCompressed() || A.rows() != A.cols() || A.rows() % 3 != 0) return false;
  const Eigen::Index n = A.rows() / 3;
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* v = A.valuePtr();
  offsets_.resize(static_cast<size_t>(n) + 1);
  for (Eigen::Index r = 0; r < n; ++r) {
    const int m = outer[3 * r + 1] - outer[3 * r];
    if (m % 3 != 0 || outer[3 * r + 2] - outer[3 * r + 1] != m || outer[3 * r + 3] - outer[3 * r + 2] != m) {
      offsets_.assign(1, 0);
      return false;
    }
    offsets_[static_cast<size_t>(r) + 1] = offsets_[static_cast<size_t>(r)] + m / 3;
  }
  columns_.resize(static_cast<size_t>(offsets_.back()));
  values_.resize(9 * columns_.size());
  std::atomic<bool> blocks{true};
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, n, 256), [&](const auto& range) {
    for (Eigen::Index r = range.begin(); r != range.end(); ++r) {
      const int first = offsets_[static_cast<size_t>(r)], count = offsets_[static_cast<size_t>(r) + 1] - first;
      for (int k = 0; k < 3; ++k) {
        const int base = outer[3 * r + k];
        for (int b = 0; b < count; ++b) {
          const int i = inner[base + 3 * b];
          if (i % 3 != 0 || inner[base + 3 * b + 1] != i + 1 || inner[base + 3 * b + 2] != i + 2 ||
              (k > 0 && columns_[static_cast<size_t>(first + b)] != i / 3)) {
            blocks = false;
            return;
          }
          if (k == 0) columns_[static_cast<size_t>(first + b)] = i / 3;
          // Column 3r + k holds A(3c + j, 3r + k) = A(3r + k, 3c + j): row k of block (r, c).
          float* row = &values_[9 * static_cast<size_t>(first + b) + 3 * static_cast<size_t>(k)];
          for (int j = 0; j < 3; ++j) row[j] = static_cast<float>(v[base + 3 * b + j]);
        }
      }
    }
  });
  if (!blocks) {
    offsets_.assign(1, 0);
    columns_.clear();
    values_.clear();
  }
  return blocks;
}

void SinglePrecisionBlockRows::apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const Eigen::Index n = static_cast<Eigen::Index>(offsets_.size()) - 1;
  y.resize(3 * n);
  const double* xs = x.data();
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, n, 256), [&](const auto& range) {
    for (Eigen::Index r = range.begin(); r != range.end(); ++r) {
      double s0 = 0.0, s1 = 0.0, s2 = 0.0;
      for (int b = offsets_[static_cast<size_t>(r)]; b < offsets_[static_cast<size_t>(r) + 1]; ++b) {
        const float* B = &values_[9 * static_cast<size_t>(b)];
        const double* xc = xs + 3 * static_cast<Eigen::Index>(columns_[static_cast<size_t>(b)]);
        const double x0 = xc[0], x1 = xc[1], x2 = xc[2];
        s0 += double(B[0]) * x0 + double(B[1]) * x1 + double(B[2]) * x2;
        s1 += double(B[3]) * x0 + double(B[4]) * x1 + double(B[5]) * x2;
        s2 += double(B[6]) * x0 + double(B[7]) * x1 + double(B[8]) * x2;
      }
      y[3 * r] = s0;
      y[3 * r + 1] = s1;
      y[3 * r + 2] = s2;
    }
  });
}

std::size_t SinglePrecisionBlockRows::bytes() const {
  return offsets_.size() * sizeof(int) + columns_.size() * sizeof(int) + values_.size() * sizeof(float);
}

}  // namespace sinew
