#include "sinew/material/families/neo_hookean_ogden.hpp"

#include <cmath>

namespace sinew {

// Psi = mu/2 (I_C - 3) - mu log J + lambda/2 (J - 1)^2
InvariantMaterial::Derivatives NeoHookeanOgden::invariant_derivatives(double Ic, double J) const {
  Derivatives d;
  d.psi = 0.5 * mu_ * (Ic - 3.0) - mu_ * std::log(J) + 0.5 * lambda_ * (J - 1.0) * (J - 1.0);
  d.dI = 0.5 * mu_;
  d.dJ = lambda_ * (J - 1.0) - mu_ / J;
  d.dJJ = lambda_ + mu_ / (J * J);
  return d;
}

Evaluation NeoHookeanOgden::evaluate_impl(const Mat3& F, Projection mode) const {
  Evaluation e;
  e.psi = psi_impl(F);
  e.P = pk1_impl(F);
  e.hessian = mode == Projection::None ? hessian_impl(F)
                                       : eigensystem_impl(F).projected(mode, projection_floor());
  return e;
}

}  // namespace sinew
