#pragma once
// Hyperelastic energy of a mesh: sum over elements and quadrature points of w Psi(F).
#include <memory>

#include "sinew/element/discretization.hpp"
#include "sinew/forms/element_form.hpp"
#include "sinew/material/material.hpp"

namespace sinew {

class ElasticForm final : public ElementForm {
 public:
  ElasticForm(std::shared_ptr<const Discretization> disc, std::shared_ptr<const Material> material,
              Projection projection = Projection::Clamp);

  std::string name() const override { return "elastic"; }
  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override;
  bool is_valid(const Eigen::VectorXd& x) const override;

  // Per-element fields for output: energy (integrated), mean J, volume-averaged energy
  // density and Frobenius norm of P.
  struct ElementFields {
    Eigen::VectorXd energy, J, energy_density, stress_norm;
  };
  ElementFields element_fields(const Eigen::VectorXd& x) const;

  // Per element: U_e = sum_q w_q Psi(F_q), its exact gradient sum_q w_q P(F_q) dN/dX, and
  // sum_q w_q dF/dx^T proj(d2Psi/dF2) dF/dx with the form's projection.
  const Discretization& discretization() const override { return *disc_; }
  double element_value(Eigen::Index e, const Eigen::VectorXd& x) const override;
  Eigen::VectorXd element_gradient(Eigen::Index e, const Eigen::VectorXd& x,
                                   JacobianKind kind = JacobianKind::Exact) const override;
  Eigen::MatrixXd element_hessian(Eigen::Index e, const Eigen::VectorXd& x) const override;

  const Material& material() const { return *material_; }

 private:
  std::shared_ptr<const Discretization> disc_;
  std::shared_ptr<const Material> material_;
  Projection projection_;
};

}  // namespace sinew
