#include "sinew/assembly/matrix_free_hessian.hpp"

#include "sinew/assembly/problem.hpp"

namespace sinew {

MatrixFreeHessian::MatrixFreeHessian(const Problem& problem, const BlockHessian& assembled,
                                     std::vector<const Form*> products)
    : problem_(&problem), assembled_(&assembled), products_(std::move(products)) {
  const Eigen::Index vertices = rows() / 3;
  diagonal_.resize(static_cast<size_t>(vertices));
  for (Eigen::Index v = 0; v < vertices; ++v) diagonal_[static_cast<size_t>(v)] = assembled.diagonal_block(static_cast<int>(v));
  for (const Form* f : products_) f->add_hessian_diagonal(diagonal_);
  const std::vector<char>& fixed = problem.fixed();
  for (Eigen::Index v = 0; v < vertices; ++v) {
    Mat3& D = diagonal_[static_cast<size_t>(v)];
    if (const Mat3* Q = problem.vertex_frame(v)) D = Q->transpose() * D * *Q;
    for (int i = 0; i < 3; ++i)
      if (fixed[static_cast<size_t>(3 * v + i)]) {
        D.row(i).setZero();
        D.col(i).setZero();
        D(i, i) = 1.0;
      }
  }
}

void MatrixFreeHessian::apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  const std::vector<char>& fixed = problem_->fixed();
  // A_local = Q^T A Q with fixed rows and columns replaced by the identity.
  global_ = x;
  for (Eigen::Index i = 0; i < global_.size(); ++i)
    if (fixed[static_cast<size_t>(i)]) global_[i] = 0.0;
  problem_->to_global(global_);
  assembled_->multiply(global_, y);
  for (const Form* f : products_) f->add_hessian_product(global_, y);
  problem_->to_local(y);
  for (Eigen::Index i = 0; i < y.size(); ++i)
    if (fixed[static_cast<size_t>(i)]) y[i] = x[i];
}

}  // namespace sinew
