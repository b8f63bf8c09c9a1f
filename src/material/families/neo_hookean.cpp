#include "sinew/material/families/neo_hookean.hpp"

#include <cmath>

namespace sinew {

// Psi = mu/2 (I_C - 3) - mu log J + lambda/2 log^2 J
InvariantMaterial::Derivatives NeoHookean::invariant_derivatives(double Ic, double J) const {
  const double L = std::log(J);
  Derivatives d;
  d.psi = 0.5 * mu_ * (Ic - 3.0) - mu_ * L + 0.5 * lambda_ * L * L;
  d.dI = 0.5 * mu_;
  d.dJ = (lambda_ * L - mu_) / J;
  d.dJJ = (mu_ + lambda_ * (1.0 - L)) / (J * J);
  return d;
}

Evaluation NeoHookean::evaluate_impl(const Mat3& F, Projection mode) const {
  Evaluation e;
  e.psi = psi_impl(F);
  e.P = pk1_impl(F);
  e.hessian = mode == Projection::None ? hessian_impl(F)
                                       : eigensystem_impl(F).projected(mode, projection_floor());
  return e;
}

}  // namespace sinew
