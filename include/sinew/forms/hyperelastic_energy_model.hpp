#pragma once
// Any hyperelastic material of the library as an ElementEnergyModel: U_e = sum_q w_q Psi(F_q),
// its exact gradient sum_q w_q P(F_q) dN/dX as the constraint Jacobian, forces and the
// PSD-projected Hessian from ElasticForm. There is no rotation, so only JacobianKind::Exact.
#include "sinew/forms/element_energy_model.hpp"
#include "sinew/forms/elastic_form.hpp"

namespace sinew {

class HyperelasticEnergyModel final : public ElementEnergyModel {
 public:
  HyperelasticEnergyModel(std::shared_ptr<const Discretization> disc, std::shared_ptr<const Material> material);

  std::string name() const override { return "hyperelastic:" + form_.material().name(); }
  const Discretization& discretization() const override { return form_.discretization(); }

  double element_energy(Eigen::Index e, const Eigen::VectorXd& x) const override;
  Eigen::VectorXd element_energy_gradient(Eigen::Index e, const Eigen::VectorXd& x,
                                          JacobianKind kind) const override;
  bool supports(JacobianKind kind) const override { return kind == JacobianKind::Exact; }
  // sum_q w_q dF/dx^T proj(d2Psi/dF2) dF/dx, eigenvalues clamped at zero.
  Eigen::MatrixXd element_energy_hessian(Eigen::Index e, const Eigen::VectorXd& x) const override;

  Eigen::VectorXd forces(const Eigen::VectorXd& x) const override;
  Eigen::SparseMatrix<double> stiffness(const Eigen::VectorXd& x) const override;

 private:
  ElasticForm form_;
  std::vector<std::vector<int>> cliques_;
};

}  // namespace sinew
