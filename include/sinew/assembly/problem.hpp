#pragma once
// The total energy as a sum of forms over a DOF vector, with Dirichlet (fixed) DOFs.
// Fixed DOFs keep whatever value x holds; the gradient is zero there and the Hessian's
// fixed rows/columns are replaced by the identity, so the pattern never changes.
// Vertices may have their DOFs expressed in a rotated frame (a roller on an inclined plane
// fixes only the first axis of its frame): gradient() and hessian() are then in those local
// coordinates, the fixed mask refers to them, and to_global() maps a step back.
#include <memory>
#include <vector>

#include "sinew/element/discretization.hpp"
#include "sinew/linalg/block_hessian.hpp"
#include "sinew/forms/form.hpp"
#include "sinew/linalg/linear_operator.hpp"
#include "sinew/assembly/matrix_free_hessian.hpp"

namespace sinew {

class Problem {
 public:
  explicit Problem(Eigen::Index num_vertices);

  void add_form(std::shared_ptr<Form> form);
  const std::vector<std::shared_ptr<Form>>& forms() const { return forms_; }
  Eigen::Index num_dofs() const { return 3 * num_vertices_; }

  void set_fixed(const std::vector<char>& fixed_dofs);  // one flag per DOF
  const std::vector<char>& fixed() const { return fixed_; }

  // Orthonormal frames (columns = local axes) of the vertices whose DOFs are rotated.
  void set_vertex_frames(const std::vector<std::pair<int, Mat3>>& frames);
  bool has_vertex_frames() const { return !frame_of_.empty(); }
  // The frame of vertex v, or null if its DOFs are not rotated.
  const Mat3* vertex_frame(Eigen::Index v) const { return frame_of_.empty() ? nullptr : frame_of_[static_cast<size_t>(v)]; }
  // A vector in local DOFs (a Newton step) to global coordinates, in place.
  void to_global(Eigen::VectorXd& d) const;
  // Global coordinates to local DOFs (a gradient), in place.
  void to_local(Eigen::VectorXd& g) const;

  // Characteristic scales of the problem for dimensionless convergence tests: a length (the
  // body's size) and a force (stiffness times size squared). Zero when unknown.
  struct Scales {
    double length = 0.0;
    double force = 0.0;
  };
  void set_scales(const Scales& scales) { scales_ = scales; }
  const Scales& scales() const { return scales_; }

  // The discretisation the DOFs belong to, when there is one (solvers may use it and its
  // lattice; solver/solver_context.hpp). It must have this problem's vertex count.
  void set_discretization(std::shared_ptr<const Discretization> discretization);
  const std::shared_ptr<const Discretization>& discretization() const { return discretization_; }

  double value(const Eigen::VectorXd& x) const;            // +inf where some form is invalid
  Eigen::VectorXd gradient(const Eigen::VectorXd& x) const;  // zero at fixed DOFs
  // The same, also returning the largest force any single form exerts (the 2-norm of its
  // unconstrained gradient): a force scale of the current state (loads, internal forces, the
  // reactions they imply, inertia) for relative convergence tests.
  Eigen::VectorXd gradient(const Eigen::VectorXd& x, double& force_scale) const;
  // The projected Hessian with Dirichlet rows/columns replaced by the identity, as an operator
  // (valid until the next call). First calls Form::linearize_at(x) on every form: x is the
  // point the next search direction starts from.
  // exact = true: every form's true Hessian (Form::add_exact_hessian), which may be indefinite.
  const LinearOperator& hessian(const Eigen::VectorXd& x, bool exact = false);
  bool is_valid(const Eigen::VectorXd& x) const;

  // Matrix-free Newton systems: hessian() then keeps the Hessians of the forms that support it
  // as element matrices (Form::supports_hessian_product) and assembles only the others; the
  // operator has no matrix(), so only CG with a diagonal-type preconditioner can use it.
  void set_matrix_free(bool on);
  bool matrix_free() const { return matrix_free_; }
  // Bytes the last hessian() keeps: the assembled matrix (values and indices) plus the forms'
  // element matrices.
  std::size_t hessian_bytes() const;
  // Form::refresh on every form; true if any energy changed.
  bool refresh(const Eigen::VectorXd& x);
  // Form::add_at_iterate on every form (after an accepted Newton step); true if any energy changed.
  bool add_at_iterate(const Eigen::VectorXd& x);
  // Form::begin_solve on every form (a Newton solve's first iteration); true if any energy changed.
  bool begin_solve(const Eigen::VectorXd& x);

 private:
  void ensure_pattern();
  // One of Form's lagged-state hooks on every form; the Hessian pattern is rebuilt if couplings changed.
  bool refresh_forms(const Eigen::VectorXd& x, bool (Form::*hook)(const Eigen::VectorXd&));
  Eigen::Index num_vertices_;
  std::vector<std::shared_ptr<Form>> forms_;
  std::vector<char> fixed_;
  std::vector<Mat3> frames_;              // rotated vertex frames
  std::vector<int> framed_vertices_;      // their vertices
  std::vector<const Mat3*> frame_of_;     // per vertex, null if unrotated (empty if none)
  Scales scales_;
  std::shared_ptr<const Discretization> discretization_;
  std::unique_ptr<BlockHessian> hessian_;
  std::unique_ptr<BlockHessianOperator> hessian_operator_;
  bool matrix_free_ = false;
  std::unique_ptr<MatrixFreeHessian> matrix_free_operator_;
};

}  // namespace sinew
