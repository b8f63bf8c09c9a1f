#include "sinew/forms/external_force_form.hpp"

namespace sinew {

Eigen::VectorXd gravity_forces(const Eigen::VectorXd& m, const Eigen::Vector3d& g) {
  Eigen::VectorXd f(3 * m.size());
  for (Eigen::Index v = 0; v < m.size(); ++v) f.segment<3>(3 * v) = m(v) * g;
  return f;
}

}  // namespace sinew
