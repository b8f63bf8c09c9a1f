#include "sinew/material/families/fung.hpp"

#include <cmath>

#include "sinew/core/error.hpp"

namespace sinew {

Fung::Fung(double mu0, double mu1, double gamma, double lambda)
    : mu0_(mu0), mu1_(mu1), gamma_(gamma), lambda_(lambda), volume_{lambda, mu0 + gamma * mu1} {
  if (lambda == 0.0) {
    throw Error("must be nonzero: alpha = 1 + (mu0 + gamma mu1)/lambda divides by it", "lambda");
  }
  rest_psi_ = terms(3.0, 1.0).psi;
}

GeneralModelMaterial::Terms Fung::terms(double Ic, double J) const {
  const double e = std::exp(0.5 * mu1_ * (Ic - 3.0));
  Terms t;
  t.psi = 0.5 * mu0_ * (Ic - 3.0) + volume_.psi(J) + gamma_ * (e - 1.0) - rest_psi_;  // Eq. 53
  t.dI = 0.5 * (mu0_ + gamma_ * mu1_ * e);  // 2 Psi_I = mu_T (Eq. 54, 56)
  t.dII = 0.25 * gamma_ * mu1_ * mu1_ * e;  // 4 Psi_II = gamma mu1^2 e (see docs: not Eq. 55's 2x)
  t.dJ = volume_.dJ(J);
  t.dJJ = volume_.dJJ();
  return t;
}

}  // namespace sinew
