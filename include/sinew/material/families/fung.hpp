#pragma once
#include <string>

#include "sinew/material/families/general_model.hpp"

namespace sinew {

// Stabilised Fung hardening (paper 000 Eq. 53-56):
//   Psi = mu0/2 (I_C - 3) + lambda/2 (J - alpha)^2 + gamma (exp(mu1/2 (I_C - 3)) - 1),
//   alpha = 1 + (mu0 + gamma mu1) / lambda,
// the form whose PK1 is Eq. 54, P = mu0 F + lambda (J - alpha) dJ/dF + gamma mu1 e F.
// lambda_Lame = lambda + gamma mu1^2 - mu0 - gamma mu1, mu_Lame = mu0 + gamma mu1.
// General-model eigensystem with gamma_I = mu0 + gamma mu1 e, gamma_F = gamma mu1^2 e,
// gamma_G = lambda, gamma_H = lambda (J - alpha), e = exp(mu1/2 (I_C - 3)).
class Fung final : public GeneralModelMaterial {
 public:
  Fung(double mu0, double mu1, double gamma, double lambda);
  std::string name() const override { return "fung"; }
  Terms terms(double Ic, double J) const override;

 private:
  double mu0_, mu1_, gamma_, lambda_;
  ShiftedVolume volume_;
  double rest_psi_ = 0.0;  // subtracted so that Psi(I) = 0 (constants do not change forces)
};

}  // namespace sinew
