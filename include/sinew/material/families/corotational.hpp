#pragma once
#include "sinew/material/material.hpp"

namespace sinew {

// Co-rotational elasticity (paper 000 Eq. 3; paper 002 Table 1 "Linear Corotational"):
//   Psi = mu ||F - R||_F^2 + lambda/2 tr^2(S - I)
//       = mu sum_i (sigma_i - 1)^2 + lambda/2 (sigma_0 + sigma_1 + sigma_2 - 3)^2.
// Defined for every F; lambda_Lame = lambda, mu_Lame = mu.
class LinearCorotational final : public StretchMaterial {
 public:
  LinearCorotational(double lambda, double mu, std::string name = "linear_corotational")
      : lambda_(lambda), mu_(mu), name_(std::move(name)) {}
  std::string name() const override { return name_; }

  double psi_stretch(const Vec3& s) const override;
  Vec3 grad_stretch(const Vec3& s) const override;
  Mat3 hess_stretch(const Vec3& s) const override;
  // Closed form; the twist quotient is singular where sigma_i = -sigma_j (R jumps there).
  void pair_eigenvalues(const Vec3& s, const Vec3& p, const Mat3& h, Vec3& twist,
                        Vec3& flip) const override;

 private:
  double lambda_, mu_;
  std::string name_;
};

}  // namespace sinew
