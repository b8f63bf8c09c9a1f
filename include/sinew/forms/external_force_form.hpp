#pragma once
// Potential of constant external forces (gravity, point loads, tractions): E = -f . x.
#include "sinew/forms/form.hpp"

namespace sinew {

class ExternalForceForm final : public Form {
 public:
  explicit ExternalForceForm(Eigen::VectorXd forces) : f_(std::move(forces)) {}
  std::string name() const override { return "external"; }
  double value(const Eigen::VectorXd& x) const override { return -f_.dot(x); }
  void add_gradient(const Eigen::VectorXd&, Eigen::VectorXd& g) const override { g -= f_; }
  void add_hessian(const Eigen::VectorXd&, BlockHessian&) const override {}
  Eigen::VectorXd& forces() { return f_; }
  const Eigen::VectorXd& forces() const { return f_; }

 private:
  Eigen::VectorXd f_;
};

// Gravity on lumped masses: f_v = m_v g.
Eigen::VectorXd gravity_forces(const Eigen::VectorXd& lumped_masses, const Eigen::Vector3d& g);

}  // namespace sinew
