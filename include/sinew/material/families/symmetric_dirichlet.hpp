#pragma once
#include "sinew/material/separable.hpp"

namespace sinew {

// Symmetric Dirichlet (Smith and Schaefer 2015; paper 002 Table 1) with a scale mu (mu = 1
// is the table's 1/2 (||F||^2 + ||F^-1||^2) - 3):
//   Psi = mu/2 sum_i (s_i - 1/s_i)^2.   lambda_Lame = 0, mu_Lame = 2 mu. J > 0 only.
class SymmetricDirichlet final : public SeparableStretchMaterial {
 public:
  explicit SymmetricDirichlet(double mu) : mu_(mu) {}
  std::string name() const override { return "symmetric_dirichlet"; }
  Domain domain() const override { return Domain::PositiveJ; }

 protected:
  Vec3 single(double s) const override;
  double single_flip(double x, double y) const override;
  double single_twist(double x, double y) const override;

 private:
  double mu_;
};

}  // namespace sinew
