#pragma once
#include <string>

#include "sinew/material/material.hpp"

namespace sinew {

// "Fixed" co-rotational elasticity (Stomakhin et al. 2012; paper 000 Eq. 49):
//   Psi = mu ||F - R||_F^2 + lambda/2 (J - 1)^2 = mu sum_i (sigma_i - 1)^2 + lambda/2 (J - 1)^2.
// Defined for every F; lambda_Lame = lambda, mu_Lame = mu.
class FixedCorotational final : public StretchMaterial {
 public:
  FixedCorotational(double lambda, double mu) : lambda_(lambda), mu_(mu) {}
  std::string name() const override { return "fixed_corotational"; }

  double psi_stretch(const Vec3& s) const override;
  Vec3 grad_stretch(const Vec3& s) const override;
  Mat3 hess_stretch(const Vec3& s) const override;
  // Closed form; the twist value is singular at sigma_i = -sigma_j, where R jumps.
  void pair_eigenvalues(const Vec3& s, const Vec3& p, const Mat3& h, Vec3& twist,
                        Vec3& flip) const override;

 private:
  double lambda_, mu_;
};

}  // namespace sinew
