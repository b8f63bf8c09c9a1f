#pragma once
#include <string>

#include "sinew/material/families/general_model.hpp"

namespace sinew {

// Stabilised three-term Arruda-Boyce (paper 000 Eq. 58-61):
//   Psi = mu/2 (I_C - 3) + mu beta1/4 (I_C^2 - 9) + mu beta2/6 (I_C^3 - 27)
//         + lambda/2 (J - alpha)^2,   alpha = 1 + mu/lambda (1 + 3 beta1 + 9 beta2).
// lambda_Lame = lambda + 2 mu (beta1 + 6 beta2) - mu (1 + 3 beta1 + 9 beta2),
// mu_Lame = mu (1 + 3 beta1 + 9 beta2).
// General-model eigensystem (Eq. 61): gamma_I = mu (1 + beta1 I_C + beta2 I_C^2),
// gamma_F = 2 mu (beta1 + 2 beta2 I_C), gamma_G = lambda, gamma_H = lambda (J - alpha).
class ArrudaBoyce final : public GeneralModelMaterial {
 public:
  ArrudaBoyce(double lambda, double mu, double beta1, double beta2);
  std::string name() const override { return "arruda_boyce"; }
  Terms terms(double Ic, double J) const override;

 private:
  double lambda_, mu_, beta1_, beta2_;
  ShiftedVolume volume_;
  double rest_psi_ = 0.0;  // subtracted so that Psi(I) = 0 (constants do not change forces)
};

}  // namespace sinew
