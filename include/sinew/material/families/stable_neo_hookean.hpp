#pragma once
#include <string>

#include "sinew/material/families/general_model.hpp"

namespace sinew {

// Stable Neo-Hookean (paper 000 Eq. 14):
//   Psi = mu/2 (I_C - 3) + lambda/2 (J - alpha)^2 - mu/2 log(I_C + 1),
//   alpha = 1 + mu/lambda - mu/(4 lambda) = 1 + 3 mu / (4 lambda).
// lambda and mu are the model's own parameters, not Lamé's (§3.4):
//   lambda_Lame = lambda - 5/8 mu, mu_Lame = 3/4 mu.
// Defined for every F (I_C + 1 >= 1). Eigensystem: §4.6 closed form (Eq. 42-48) with
//   gamma_I = mu_T = mu (1 - 1/(I_C + 1)), gamma_F = 2 mu / (I_C + 1)^2,
//   gamma_G = lambda, gamma_H = lambda (J - alpha).
// lambda must be nonzero (alpha and Eq. 14's constant lambda/2 (1 - alpha)^2 divide by it).
class StableNeoHookean final : public GeneralModelMaterial {
 public:
  StableNeoHookean(double lambda, double mu);
  std::string name() const override { return "stable_neo_hookean"; }
  Terms terms(double Ic, double J) const override;
  Terms curvature_terms(double Ic, double J) const override;  // no log
  void curvature_derivatives_at(int n, const double* Ic, const double* J, Derivatives* out) const override;
  double alpha() const { return 1.0 + 0.75 * mu_ / lambda_; }

 private:
  double lambda_, mu_;
  ShiftedVolume volume_;
  double rest_psi_ = 0.0;  // subtracted so that Psi(I) = 0 (constants do not change forces)
};

}  // namespace sinew
