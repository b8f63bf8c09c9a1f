#pragma once
// The total energy as a sum of forms over a DOF vector, with Dirichlet (fixed) DOFs.
// Fixed DOFs keep whatever value x holds; the gradient is zero there and the Hessian's
// fixed rows/columns are replaced by the identity, so the pattern never changes.
#include <memory>
#include <vector>

#include "sinew/linalg/block_hessian.hpp"
#include "sinew/forms/form.hpp"
#include "sinew/linalg/linear_operator.hpp"

namespace sinew {

class Problem {
 public:
  explicit Problem(Eigen::Index num_vertices);

  void add_form(std::shared_ptr<Form> form);
  const std::vector<std::shared_ptr<Form>>& forms() const { return forms_; }
  Eigen::Index num_dofs() const { return 3 * num_vertices_; }

  void set_fixed(const std::vector<char>& fixed_dofs);  // one flag per DOF
  const std::vector<char>& fixed() const { return fixed_; }

  double value(const Eigen::VectorXd& x) const;            // +inf where some form is invalid
  Eigen::VectorXd gradient(const Eigen::VectorXd& x) const;  // zero at fixed DOFs
  // The projected Hessian with Dirichlet rows/columns replaced by the identity, as an operator
  // (valid until the next call).
  const LinearOperator& hessian(const Eigen::VectorXd& x);
  bool is_valid(const Eigen::VectorXd& x) const;
  // Form::refresh on every form; true if any energy changed.
  bool refresh(const Eigen::VectorXd& x);
  // Form::begin_solve on every form (a Newton solve's first iteration); true if any energy changed.
  bool begin_solve(const Eigen::VectorXd& x);

 private:
  void ensure_pattern();
  bool refresh_forms(const Eigen::VectorXd& x, bool start_of_solve);
  Eigen::Index num_vertices_;
  std::vector<std::shared_ptr<Form>> forms_;
  std::vector<char> fixed_;
  std::unique_ptr<BlockHessian> hessian_;
  std::unique_ptr<SparseOperator> hessian_operator_;
};

}  // namespace sinew
