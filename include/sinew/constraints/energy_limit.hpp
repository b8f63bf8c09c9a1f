#pragma once
// Energy-limiting constraints (paper 001 §4): per element C_e = 1 - U_e/U_max >= 0 (Eq. 14)
// and its Jacobian dC_e/dx = -dU_e/dx / U_max (Eq. 15), exact or warped-force.
#include "sinew/forms/element_form.hpp"

namespace sinew {

struct EnergyLimit {
  double max_energy = 0.0;  // U_max in joules, > 0
  JacobianKind jacobian = JacobianKind::Exact;
};

double energy_constraint(const ElementForm& form, Eigen::Index e, const Eigen::VectorXd& x,
                         double max_energy);
// Over the element's nodes (3 * nodes entries, node-major).
Eigen::VectorXd energy_constraint_jacobian(const ElementForm& form, Eigen::Index e,
                                           const Eigen::VectorXd& x, const EnergyLimit& limit);

}  // namespace sinew
