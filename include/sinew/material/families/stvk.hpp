#pragma once
#include <string>

#include "sinew/material/material.hpp"

namespace sinew {

// St. Venant-Kirchhoff (paper 000 Eq. 50; paper 002 Table 1):
//   Psi = mu ||E||_F^2 + lambda/2 tr^2(E),  E = (F^T F - I)/2,
//   in stretches e_i = (sigma_i^2 - 1)/2: Psi = mu sum e_i^2 + lambda/2 (sum e_i)^2.
// Defined for every F; lambda_Lame = lambda, mu_Lame = mu.
class StVK : public StretchMaterial {
 public:
  StVK(double lambda, double mu) : lambda_(lambda), mu_(mu) {}
  std::string name() const override { return "stvk"; }

  double psi_stretch(const Vec3& s) const override;
  Vec3 grad_stretch(const Vec3& s) const override;
  Mat3 hess_stretch(const Vec3& s) const override;
  // Exact polynomials, no divided differences:
  //   flip = mu (s_i^2 + s_i s_j + s_j^2 - 1) + lambda tr E, twist = mu (s_i^2 - s_i s_j + s_j^2 - 1) + lambda tr E.
  void pair_eigenvalues(const Vec3& s, const Vec3& p, const Mat3& h, Vec3& twist,
                        Vec3& flip) const override;

 protected:
  double lambda_, mu_;
};

}  // namespace sinew
