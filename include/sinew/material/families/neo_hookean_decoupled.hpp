#pragma once
#include "sinew/material/material.hpp"

namespace sinew {

// Neo-Hookean with a deviatoric/volumetric split, as CalculiX (*HYPERELASTIC, NEO HOOKE),
// Abaqus and FEBio (coupled off) define it:
//   Psi = C10 (I1bar - 3) + (J - 1)^2 / D1,   I1bar = J^(-2/3) I_C.
// Small strain: mu_Lame = 2 C10, bulk modulus K = 2 / D1, lambda_Lame = 2/D1 - 4/3 C10.
// From (E, nu): C10 = E / (4 (1 + nu)), D1 = 6 (1 - 2 nu) / E. J > 0 only.
class NeoHookeanDecoupled final : public InvariantMaterial {
 public:
  NeoHookeanDecoupled(double C10, double D1) : C10_(C10), D1_(D1) {}
  std::string name() const override { return "neo_hookean_decoupled"; }
  Domain domain() const override { return Domain::PositiveJ; }
  Derivatives invariant_derivatives(double Ic, double J) const override;

 private:
  double C10_, D1_;
};

}  // namespace sinew
