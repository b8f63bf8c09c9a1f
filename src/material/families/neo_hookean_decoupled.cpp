#include "sinew/material/families/neo_hookean_decoupled.hpp"

#include <cmath>

namespace sinew {

// Psi = C10 (J^(-2/3) I_C - 3) + (J - 1)^2 / D1:
//   Psi_I  = C10 J^(-2/3),               Psi_II = 0,
//   Psi_J  = -2/3 C10 I_C J^(-5/3) + 2 (J - 1) / D1,
//   Psi_IJ = -2/3 C10 J^(-5/3),          Psi_JJ = 10/9 C10 I_C J^(-8/3) + 2 / D1.
InvariantMaterial::Derivatives NeoHookeanDecoupled::invariant_derivatives(double Ic, double J) const {
  const double a = std::pow(J, -2.0 / 3.0);  // J^(-2/3)
  Derivatives d;
  d.psi = C10_ * (a * Ic - 3.0) + (J - 1.0) * (J - 1.0) / D1_;
  d.dI = C10_ * a;
  d.dJ = -2.0 / 3.0 * C10_ * Ic * a / J + 2.0 * (J - 1.0) / D1_;
  d.dII = 0.0;
  d.dIJ = -2.0 / 3.0 * C10_ * a / J;
  d.dJJ = 10.0 / 9.0 * C10_ * Ic * a / (J * J) + 2.0 / D1_;
  return d;
}

}  // namespace sinew
