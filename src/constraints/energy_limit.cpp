#include "sinew/constraints/energy_limit.hpp"

namespace sinew {

double energy_constraint(const ElementEnergyModel& model, Eigen::Index e, const Eigen::VectorXd& x,
                         double max_energy) {
  return 1.0 - model.element_energy(e, x) / max_energy;  // Eq. 14
}

Eigen::VectorXd energy_constraint_jacobian(const ElementEnergyModel& model, Eigen::Index e,
                                           const Eigen::VectorXd& x, const EnergyLimit& limit) {
  return -model.element_energy_gradient(e, x, limit.jacobian) / limit.max_energy;  // Eq. 15
}

}  // namespace sinew
