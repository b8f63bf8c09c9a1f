#pragma once
// The derivative checker of energy terms (FEBio's tangent diagnostic): a Form's gradient against
// central differences of its value and its exact Hessian against central differences of its
// gradient, at a state x, along every coordinate direction (small problems) or along random
// unit directions (large ones). Forms whose Hessian is projected to PSD are also checked for
// a symmetric PSD projected Hessian. Used by every form test and by `sinew check`.
#include <Eigen/Core>
#include <string>

#include "sinew/forms/form.hpp"

namespace sinew {

struct FormCheckOptions {
  // The step: `step` when > 0, otherwise relative_step times the extent of x (the largest side of
  // the bounding box of x read as points x[3v..3v+2]; 1 for a degenerate x).
  double step = 0.0;
  double relative_step = 1e-6;
  bool richardson = true;  // one Richardson step (error O(h^4)) on each central difference
  // Up to this many DOFs, every coordinate direction; above, `random_directions` random unit
  // directions (normally distributed, from `seed`).
  Eigen::Index max_coordinate_dofs = 600;
  int random_directions = 8;
  unsigned seed = 1;
  // The projected Hessian's smallest eigenvalue by a dense eigensolve up to this many DOFs;
  // above, the smallest Rayleigh quotient over the random directions.
  Eigen::Index max_dense_dofs = 1500;
  double tolerance = 1e-5;  // pass/fail of FormCheck::passed
};

// What the checker measured: k directions (columns of `directions`, unit length), the analytic
// directional derivatives and their differences.
struct FormDifferences {
  double step = 0.0;
  bool coordinate = false;           // directions are the coordinate axes, in DOF order
  Eigen::MatrixXd directions;        // n x k
  Eigen::VectorXd gradient;          // g . d_k
  Eigen::VectorXd gradient_fd;       // (E(x + h d_k) - E(x - h d_k)) / 2h
  Eigen::MatrixXd hessian;           // H_exact d_k
  Eigen::MatrixXd hessian_fd;        // (g(x + h d_k) - g(x - h d_k)) / 2h
};

FormDifferences form_differences(const Form& form, const Eigen::VectorXd& x, const FormCheckOptions& options = {});

struct FormCheck {
  std::string form;
  Eigen::Index dofs = 0;
  int directions = 0;
  bool coordinate = false;
  double step = 0.0;
  // ||a - b|| / max(||a||, ||b||, floor) over all directions, a analytic and b differenced. The
  // floors are what a difference cannot resolve: h ||H D|| (the force change over one step) for
  // the gradient, 1e-3 ||g|| / extent for the Hessian (an almost linear term); so the errors are
  // unit-free and 0 for an exactly linear term.
  double gradient_error = 0.0;
  double hessian_error = 0.0;  // of the exact Hessian (Form::add_exact_hessian)
  double asymmetry = 0.0;      // ||H - H^T|| / ||H|| of the Hessian Newton uses (add_hessian)
  // Projected forms only (Form::projects_hessian): the smallest eigenvalue of the projected
  // Hessian over ||H|| (>= -tolerance to pass), whether it is a dense eigenvalue or the smallest
  // Rayleigh quotient over the directions, and ||H_projected - H_exact|| / ||H_exact|| (zero
  // where every projected piece is already PSD).
  bool projected = false;
  bool dense_eigenvalue = false;
  double min_eigenvalue = 0.0;
  double projection_gap = 0.0;
  double tolerance = 0.0;
  bool passed() const;
};

// Checks `form` at x. Forms with lagged state (contact, inertia, damping) are checked with the
// state they hold: set it up first (begin_step, set_prediction, refresh).
FormCheck check_form(const Form& form, const Eigen::VectorXd& x, const FormCheckOptions& options = {});

// The extent of x read as 3D points (largest bounding-box side; 1 if x is a single point).
double point_extent(const Eigen::VectorXd& x);

}  // namespace sinew
