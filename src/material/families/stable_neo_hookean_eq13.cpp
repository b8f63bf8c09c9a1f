#include "sinew/material/families/stable_neo_hookean_eq13.hpp"

namespace sinew {

GeneralModelMaterial::Terms StableNeoHookeanEq13::terms(double Ic, double J) const {
  const double d = J - 1.0;
  Terms t;
  t.psi = 0.5 * mu_ * (Ic - 3.0) - mu_ * d + 0.5 * lambda_ * d * d;  // Eq. 13
  t.dI = 0.5 * mu_;                                                 // mu_T = mu (Eq. 65)
  t.dII = 0.0;                                                      // no f f^T term
  t.dJ = lambda_ * d - mu_;                                         // lambda (J - alpha)
  t.dJJ = lambda_;
  return t;
}

}  // namespace sinew
