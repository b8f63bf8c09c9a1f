#pragma once
// The derivative checker of material families: Psi -> P = dPsi/dF -> dP/dF by central
// differences (one Richardson step) at any F, inverted and near-degenerate ones included. Used by
// every material test and by the forms' checker (forms/derivative_check.hpp).
#include "sinew/core/types.hpp"
#include "sinew/material/material.hpp"

namespace sinew {

// A step that stays inside the smooth region around F: 1e-3 of the smallest singular value and,
// for inverted F, of the distance to the set sigma_i = -sigma_j where the polar rotation U V^T
// (and every energy built on it) has a Hessian singularity.
double material_difference_step(const Mat3& F);

// P from differences of psi, and the 9x9 dP/dF (column-wise vec) from differences of P.
// step <= 0: material_difference_step(F).
Mat3 difference_pk1(const Material& m, const Mat3& F, double step = 0.0);
Mat9 difference_hessian(const Material& m, const Mat3& F, double step = 0.0);

// ||a - b|| / max(||b||, floor): relative, but absolute below `floor`.
double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, double floor);

struct MaterialDerivativeCheck {
  // ||P - P_fd|| / max(||P_fd||, 1e-4 ||dP/dF||): the floor is the stress of a 1e-4 strain, so
  // a stress-free F compares absolutely and the error is free of the material's units.
  double pk1_error = 0.0;
  // ||dP/dF - (dP/dF)_fd|| / ||(dP/dF)_fd||.
  double hessian_error = 0.0;
  double step = 0.0;
  bool passed(double tolerance) const { return pk1_error <= tolerance && hessian_error <= tolerance; }
};

// Checks m.pk1 against differences of m.psi and m.hessian (the true, unprojected one) against
// differences of m.pk1 at F (which must lie in the material's domain).
MaterialDerivativeCheck check_material_derivatives(const Material& m, const Mat3& F);

}  // namespace sinew
