#include "sinew/material/families/stable_neo_hookean.hpp"

#include <cmath>

#include "sinew/core/error.hpp"

namespace sinew {

StableNeoHookean::StableNeoHookean(double lambda, double mu)
    : lambda_(lambda), mu_(mu), volume_{lambda, 0.75 * mu} {
  // lambda (alpha - 1) = mu - mu/4 (§3.3, rest stability with the origin barrier).
  if (lambda == 0.0) {
    throw Error("must be nonzero: alpha = 1 + mu/lambda - mu/(4 lambda) divides by it", "lambda");
  }
  rest_psi_ = terms(3.0, 1.0).psi;
}

GeneralModelMaterial::Terms StableNeoHookean::terms(double Ic, double J) const {
  Terms t = curvature_terms(Ic, J);
  t.psi = 0.5 * mu_ * (Ic - 3.0) + volume_.psi(J) - 0.5 * mu_ * std::log(Ic + 1.0) - rest_psi_;  // Eq. 14
  return t;
}

GeneralModelMaterial::Terms StableNeoHookean::curvature_terms(double Ic, double J) const {
  const double b = 1.0 / (Ic + 1.0);  // I_C + 1 >= 1: the barrier is regular everywhere
  Terms t;
  t.dI = 0.5 * mu_ * (1.0 - b);        // 2 Psi_I = mu_T (Eq. 18)
  t.dII = 0.5 * mu_ * b * b;           // 4 Psi_II = 2 mu / (I_C + 1)^2 (Eq. 41)
  t.dJ = volume_.dJ(J);                // lambda (J - alpha)
  t.dJJ = volume_.dJJ();
  return t;
}

void StableNeoHookean::curvature_derivatives_at(int n, const double* Ic, const double* J, Derivatives* out) const {
  for (int i = 0; i < n; ++i) out[i] = derivatives(curvature_terms(Ic[i], J[i]));  // the class is final: inlined
}

}  // namespace sinew
