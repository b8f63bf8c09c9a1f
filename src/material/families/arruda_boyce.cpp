#include "sinew/material/families/arruda_boyce.hpp"

#include "sinew/core/error.hpp"

namespace sinew {

ArrudaBoyce::ArrudaBoyce(double lambda, double mu, double beta1, double beta2)
    : lambda_(lambda),
      mu_(mu),
      beta1_(beta1),
      beta2_(beta2),
      volume_{lambda, mu * (1.0 + 3.0 * beta1 + 9.0 * beta2)} {
  if (lambda == 0.0) {
    throw Error("must be nonzero: alpha = 1 + mu/lambda (1 + 3 beta1 + 9 beta2) divides by it",
                "lambda");
  }
  rest_psi_ = terms(3.0, 1.0).psi;
}

GeneralModelMaterial::Terms ArrudaBoyce::terms(double Ic, double J) const {
  const double I2 = Ic * Ic;
  Terms t;
  t.psi = 0.5 * mu_ * (Ic - 3.0) + 0.25 * mu_ * beta1_ * (I2 - 9.0) +
          mu_ * beta2_ / 6.0 * (I2 * Ic - 27.0) + volume_.psi(J) - rest_psi_;  // Eq. 58
  t.dI = 0.5 * mu_ * (1.0 + beta1_ * Ic + beta2_ * I2);             // 2 Psi_I = mu_T (Eq. 59, 61)
  t.dII = 0.5 * mu_ * (beta1_ + 2.0 * beta2_ * Ic);                 // 4 Psi_II (Eq. 60)
  t.dJ = volume_.dJ(J);
  t.dJJ = volume_.dJJ();
  return t;
}

}  // namespace sinew
