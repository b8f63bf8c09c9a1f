#pragma once
// The Newton matrix of a Problem in matrix-free form: forms that support it (the elastic energy)
// apply their kept element matrices, the others are assembled as usual (usually a far sparser
// pattern: inertia, springs, contact), and Dirichlet DOFs and rotated vertex frames act as in the
// assembled operator (identity rows and columns, Q^T A Q). For meshes whose assembled matrix does
// not fit in memory; CG with a diagonal-type preconditioner only (no matrix()).
#include <memory>
#include <vector>

#include "sinew/core/types.hpp"
#include "sinew/forms/form.hpp"
#include "sinew/linalg/block_hessian.hpp"
#include "sinew/linalg/linear_operator.hpp"

namespace sinew {

class Problem;

class MatrixFreeHessian final : public LinearOperator {
 public:
  // `assembled`: the other forms' Hessian (global frame, no Dirichlet rows); `products`: the
  // forms whose prepared Hessians are applied. Both must outlive the operator's use.
  MatrixFreeHessian(const Problem& problem, const BlockHessian& assembled, std::vector<const Form*> products);
  ~MatrixFreeHessian() override;

  Eigen::Index rows() const override { return assembled_->matrix().rows(); }
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const override;
  Mat3 diagonal_block(Eigen::Index v) const override { return diagonal_[static_cast<size_t>(v)]; }
  // The forms' element matrices, then the assembled part's blocks as elements of one or two
  // vertices, in local frames (Q^T K Q); the Dirichlet identity rows are left out.
  const ElementMatrices* element_matrices() const override;

 private:
  class Elements;
  mutable std::unique_ptr<Elements> elements_;  // built on first use
  const Problem* problem_;
  const BlockHessian* assembled_;
  std::vector<const Form*> products_;
  std::vector<Mat3> diagonal_;  // in local frames, identity at fixed DOFs
  mutable Eigen::VectorXd global_;  // scratch: x in global coordinates, fixed entries zero
};

}  // namespace sinew
