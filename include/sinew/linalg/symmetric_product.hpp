#pragma once
// y = A x for a symmetric matrix in compressed column storage, values given separately (double,
// or a single-precision copy). Column c dotted with x is row c of A x, so the loop runs in
// parallel over columns, each entry of y written by one task with a fixed summation order.
#include <Eigen/Sparse>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace sinew {

template <class Scalar>
void symmetric_product(const Eigen::SparseMatrix<double>& A, const Scalar* values, const Eigen::VectorXd& x,
                       Eigen::VectorXd& y) {
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const int* nnz = A.innerNonZeroPtr();  // non-null only for an uncompressed matrix
  y.resize(A.rows());
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, A.outerSize(), 512), [&](const auto& range) {
    for (Eigen::Index c = range.begin(); c != range.end(); ++c) {
      const int begin = outer[c];
      const int end = nnz ? begin + nnz[c] : outer[c + 1];
      double sum = 0.0;
      for (int k = begin; k < end; ++k) sum += static_cast<double>(values[k]) * x[inner[k]];
      y[c] = sum;
    }
  });
}

}  // namespace sinew
