#pragma once
#include "sinew/material/separable.hpp"

namespace sinew {

// Hencky (paper 002 Table 1, Seth-Hill alpha = 0):
//   Psi = mu sum_i log^2 s_i + lambda/2 log^2 J.   lambda_Lame = lambda, mu_Lame = mu.
class Hencky final : public SeparableStretchMaterial {
 public:
  Hencky(double lambda, double mu) : lambda_(lambda), mu_(mu) {}
  std::string name() const override { return "hencky"; }
  Domain domain() const override { return Domain::PositiveJ; }

 protected:
  Vec3 single(double s) const override;
  Vec3 volume(double J) const override;
  double single_flip(double x, double y) const override;

 private:
  double lambda_, mu_;
};

}  // namespace sinew
