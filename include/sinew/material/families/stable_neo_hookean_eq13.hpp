#pragma once
#include <string>

#include "sinew/material/families/general_model.hpp"

namespace sinew {

// Stable Neo-Hookean without the origin barrier (paper 000 Eq. 13):
//   Psi = mu/2 (I_C - 3) - mu (J - 1) + lambda/2 (J - 1)^2
//       = mu/2 (I_C - 3) + lambda/2 (J - alpha)^2 - mu^2/(2 lambda),  alpha = 1 + mu/lambda.
// lambda_Lame = lambda - mu, mu_Lame = mu (§3.4). Defined for every F. Eigensystem: the
// rank-one update of Appendix D (Eq. 65-67): gamma_I = mu, gamma_F = 0, gamma_G = lambda,
// gamma_H = lambda (J - 1) - mu = lambda (J - alpha).
class StableNeoHookeanEq13 final : public GeneralModelMaterial {
 public:
  StableNeoHookeanEq13(double lambda, double mu) : lambda_(lambda), mu_(mu) {}
  std::string name() const override { return "stable_neo_hookean_eq13"; }
  Terms terms(double Ic, double J) const override;

 private:
  double lambda_, mu_;
};

}  // namespace sinew
