#include "sinew/constraints/energy_limit.hpp"

namespace sinew {

double energy_constraint(const ElementForm& form, Eigen::Index e, const Eigen::VectorXd& x,
                         double max_energy) {
  return 1.0 - form.element_value(e, x) / max_energy;  // Eq. 14
}

Eigen::VectorXd energy_constraint_jacobian(const ElementForm& form, Eigen::Index e,
                                           const Eigen::VectorXd& x, const EnergyLimit& limit) {
  return -form.element_gradient(e, x, limit.jacobian) / limit.max_energy;  // Eq. 15
}

}  // namespace sinew
