#pragma once
// Lamé parameters of any isotropic energy, read off its energy (paper 002 Thm. 3.1), and the
// conversions between (lambda, mu) and Young's modulus / Poisson's ratio (Eq. 14-15).
#include "sinew/material/material.hpp"

namespace sinew {

struct Lame {
  double lambda = 0.0;
  double mu = 0.0;
};

struct YoungPoisson {
  double E = 0.0;
  double nu = 0.0;
};

// lambda_Lame = d12 psi(1,1,1), mu_Lame = (d11 psi(1,1,1) - d12 psi(1,1,1)) / 2 (Eq. 3-4),
// from the material's analytic stretch Hessian at the rest shape.
Lame lame_from_energy(const Material& material);

// Eq. 14. Throws if lambda + mu == 0.
YoungPoisson young_poisson(const Lame& lame);
// Eq. 15. Requires E > 0 and -1 < nu < 0.5 (throws sinew::Error naming the field otherwise).
Lame lame_from_young_poisson(const YoungPoisson& ev);

}  // namespace sinew
