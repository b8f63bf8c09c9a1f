#include "sinew/solver/diagonal_preconditioners.hpp"

#include <Eigen/Cholesky>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "sinew/core/error.hpp"

namespace sinew {

void DiagonalPreconditioner::setup(const LinearOperator& A, const SolverContext&) {
  if (A.rows() % 3 != 0) throw Error("expects 3 DOFs per vertex", "preconditioner " + name());
  const Eigen::Index blocks = A.rows() / 3;
  inverse_.resize(static_cast<size_t>(blocks));
  const bool vertex_blocks = blocks_ == Blocks::Vertex3;
  tbb::parallel_for(Eigen::Index{0}, blocks, [&](Eigen::Index b) {
    const Mat3 D = A.diagonal_block(b);
    Mat3 inv = Mat3::Zero();
    Eigen::LLT<Mat3> llt;
    if (vertex_blocks) llt.compute(D);
    if (vertex_blocks && llt.info() == Eigen::Success) {
      inv = llt.solve(Mat3::Identity());
    } else {
      for (int i = 0; i < 3; ++i) inv(i, i) = D(i, i) > 0.0 ? 1.0 / D(i, i) : 1.0;
    }
    inverse_[static_cast<size_t>(b)] = inv;
  });
}

void DiagonalPreconditioner::apply(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
  z.resize(r.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, inverse_.size(), 1024), [&](const auto& range) {
    for (size_t b = range.begin(); b != range.end(); ++b)
      z.segment<3>(3 * static_cast<Eigen::Index>(b)) = inverse_[b] * r.segment<3>(3 * static_cast<Eigen::Index>(b));
  });
}

}  // namespace sinew
