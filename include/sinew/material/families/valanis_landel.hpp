#pragma once
#include "sinew/material/separable.hpp"

namespace sinew {

// Valanis-Landel, original (Valanis and Landel 1967; paper 002 Table 1), shifted by the
// constant 6 mu so that Psi(I) = 0 (the table's form has Psi(I) = -6 mu):
//   Psi = 2 mu sum_i (s_i (log s_i - 1) + 1) + lambda/2 log^2 J.
// lambda_Lame = lambda, mu_Lame = mu.
class ValanisLandel final : public SeparableStretchMaterial {
 public:
  ValanisLandel(double lambda, double mu) : lambda_(lambda), mu_(mu) {}
  std::string name() const override { return "valanis_landel"; }
  Domain domain() const override { return Domain::PositiveJ; }

 protected:
  Vec3 single(double s) const override;
  Vec3 volume(double J) const override;
  double single_flip(double x, double y) const override;

 private:
  double lambda_, mu_;
};

}  // namespace sinew
