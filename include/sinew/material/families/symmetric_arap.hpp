#pragma once
#include "sinew/material/separable.hpp"

namespace sinew {

// Symmetric ARAP (Shtengel et al. 2017; paper 002 Table 1):
//   Psi = mu/2 (||F - R||^2 + ||F^-1 - R^-1||^2) = mu/2 sum_i ((s_i - 1)^2 + (1 - 1/s_i)^2).
// lambda_Lame = 0, mu_Lame = mu. J > 0 only.
class SymmetricArap final : public SeparableStretchMaterial {
 public:
  explicit SymmetricArap(double mu) : mu_(mu) {}
  std::string name() const override { return "symmetric_arap"; }
  Domain domain() const override { return Domain::PositiveJ; }

 protected:
  Vec3 single(double s) const override;
  double single_flip(double x, double y) const override;
  double single_twist(double x, double y) const override;

 private:
  double mu_;
};

}  // namespace sinew
