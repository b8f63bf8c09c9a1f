#pragma once
#include "sinew/material/material.hpp"

namespace sinew {

// Neo-Hookean, Ogden's version (paper 002 Table 1):
//   Psi = mu/2 (I_C - 3) - mu log J + lambda/2 (J - 1)^2.   lambda_Lame = lambda, mu_Lame = mu.
class NeoHookeanOgden final : public InvariantMaterial {
 public:
  NeoHookeanOgden(double lambda, double mu) : lambda_(lambda), mu_(mu) {}
  std::string name() const override { return "neo_hookean_ogden"; }
  Domain domain() const override { return Domain::PositiveJ; }
  Derivatives invariant_derivatives(double Ic, double J) const override;

 protected:
  // psi and P from F directly, exactly as psi() and pk1() compute them (the base's SVD path
  // differs from them by rounding, which is all there is of P near the rest shape).
  Evaluation evaluate_impl(const Mat3& F, Projection mode) const override;

 private:
  double lambda_, mu_;
};

}  // namespace sinew
