#include "sinew/linalg/linear_operator.hpp"

#include "sinew/linalg/symmetric_product.hpp"

namespace sinew {

void SparseOperator::apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  symmetric_product(*A_, A_->valuePtr(), x, y);
}

Mat3 SparseOperator::diagonal_block(Eigen::Index v) const {
  Mat3 block = Mat3::Zero();
  for (int j = 0; j < 3; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(*A_, 3 * v + j); it; ++it)
      if (it.row() / 3 == v) block(it.row() % 3, j) = it.value();
  return block;
}

}  // namespace sinew
