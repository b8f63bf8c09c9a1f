#pragma once
#include "sinew/material/separable.hpp"

namespace sinew {

// STS material (Pai et al. 2018; paper 002 Table 1): Neo-Hookean plus a quartic term in the
// principal Green strains whose coefficient (garbled in the extracted table) is its own
// parameter mu4:
//   Psi = mu/2 (sum_i s_i^2 - 3) - mu log J + lambda/2 log^2 J + mu4/8 sum_i (s_i^2 - 1)^4.
// The quartic term is flat to third order at rest: lambda_Lame = lambda, mu_Lame = mu.
class Sts final : public SeparableStretchMaterial {
 public:
  Sts(double lambda, double mu, double mu4) : lambda_(lambda), mu_(mu), mu4_(mu4) {}
  std::string name() const override { return "sts"; }
  Domain domain() const override { return Domain::PositiveJ; }

 protected:
  Vec3 single(double s) const override;
  Vec3 volume(double J) const override;
  double single_flip(double x, double y) const override;
  double single_twist(double x, double y) const override;

 private:
  double lambda_, mu_, mu4_;
};

}  // namespace sinew
