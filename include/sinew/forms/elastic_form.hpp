#pragma once
// Hyperelastic energy of a mesh: sum over elements and quadrature points of w Psi(F).
#include <memory>

#include "sinew/element/discretization.hpp"
#include "sinew/forms/form.hpp"
#include "sinew/material/material.hpp"

namespace sinew {

class ElasticForm final : public Form {
 public:
  ElasticForm(std::shared_ptr<const Discretization> disc, std::shared_ptr<const Material> material,
              Projection projection = Projection::Clamp);

  std::string name() const override { return "elastic"; }
  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override;
  bool projects_hessian() const override { return projection_ != Projection::None; }
  void add_exact_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override;
  void couplings(std::vector<std::vector<int>>& cliques) const override;
  bool is_valid(const Eigen::VectorXd& x) const override;

  // Per-element fields for output: energy (integrated), mean J, volume-averaged energy
  // density and Frobenius norm of P.
  struct ElementFields {
    Eigen::VectorXd energy, J, energy_density, stress_norm;
  };
  ElementFields element_fields(const Eigen::VectorXd& x) const;

  const Discretization& discretization() const { return *disc_; }
  const Material& material() const { return *material_; }

 private:
  void add_hessian_projected(const Eigen::VectorXd& x, BlockHessian& H, Projection projection) const;
  std::shared_ptr<const Discretization> disc_;
  std::shared_ptr<const Material> material_;
  Projection projection_;
};

}  // namespace sinew
