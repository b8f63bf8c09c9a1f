#include "sinew/linalg/linear_operator.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sinew {

void SparseOperator::apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const Eigen::SparseMatrix<double>& A = *A_;
  y.resize(A.rows());
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* value = A.valuePtr();
  const int* nnz = A.innerNonZeroPtr();  // non-null only for an uncompressed matrix
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, A.outerSize(), 512), [&](const auto& range) {
    for (Eigen::Index c = range.begin(); c != range.end(); ++c) {
      const int begin = outer[c];
      const int end = nnz ? begin + nnz[c] : outer[c + 1];
      double sum = 0.0;
      for (int k = begin; k < end; ++k) sum += value[k] * x[inner[k]];
      y[c] = sum;
    }
  });
}

Mat3 SparseOperator::diagonal_block(Eigen::Index v) const {
  Mat3 block = Mat3::Zero();
  for (int j = 0; j < 3; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(*A_, 3 * v + j); it; ++it)
      if (it.row() / 3 == v) block(it.row() % 3, j) = it.value();
  return block;
}

}  // namespace sinew
