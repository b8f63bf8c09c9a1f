#pragma once
#include "sinew/material/separable.hpp"

namespace sinew {

// As-rigid-as-possible (Sorkine and Alexa 2007; paper 002 Table 1) with a scale mu
// (mu = 1 is the table's ||F - R||^2):
//   Psi = mu ||F - R||^2 = mu sum_i (s_i - 1)^2.   lambda_Lame = 0, mu_Lame = mu.
// Defined for every F; the twist quotient is singular where s_i = -s_j (R jumps there).
class Arap final : public SeparableStretchMaterial {
 public:
  explicit Arap(double mu) : mu_(mu) {}
  std::string name() const override { return "arap"; }

 protected:
  Vec3 single(double s) const override;
  double single_flip(double x, double y) const override;
  double single_twist(double x, double y) const override;

 private:
  double mu_;
};

}  // namespace sinew
