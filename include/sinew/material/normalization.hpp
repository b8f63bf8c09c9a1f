#pragma once
// Normalisation of a material family (paper 002 §4): choose the family's `normalized`
// parameters so that the Lamé parameters read off the energy (Eq. 3-4) equal a target,
// equivalently a target Young's modulus and Poisson's ratio (Eq. 14-15).
#include "sinew/material/catalog.hpp"
#include "sinew/material/lame.hpp"

namespace sinew {

// Returns `base` (completed with the family's defaults) with the family's `normalized`
// parameters replaced so that lame_from_energy(info.make(result)) == target. The other
// parameters and the functions stay as given.
//
// Solved by Newton's method on the 2x2 system (1x1 for one-parameter families) with a
// central-difference Jacobian; the map from parameters to Lamé parameters is affine for
// every separable family, where the difference quotient is exact and one step suffices.
//
// Throws sinew::Error (context: the material) when the family has no normalized parameters,
// when a one-parameter family (lambda_Lame identically 0) is asked for lambda_Lame != 0
// (nu != 0: mix it with a volume term instead, paper 002 §6), when the Jacobian is
// singular, or when Newton does not converge.
MaterialParameters normalize(const MaterialInfo& info, const MaterialParameters& base,
                             const Lame& target);

// The same for a target (E, nu), converted with Eq. 15 (which validates E and nu).
MaterialParameters normalize(const MaterialInfo& info, const MaterialParameters& base,
                             const YoungPoisson& target);

}  // namespace sinew
