#pragma once
#include "sinew/material/separable.hpp"

namespace sinew {

// Seth-Hill family (paper 002 Table 1, "S.H. alpha"; the exponent is called m here):
//   Psi = mu/m^2 sum_i (s_i^m - 1)^2 + lambda/(2 m^2) (sum_i s_i^m - 3)^2,   m != 0.
// m = 1 is linear corotational, m = 2 StVK. lambda_Lame = lambda, mu_Lame = mu for every m.
// Domain: all F when m is a positive integer (a polynomial in the signed stretches), else J > 0.
class SethHill final : public SeparableStretchMaterial {
 public:
  SethHill(double lambda, double mu, double m);  // throws sinew::Error for m == 0
  std::string name() const override { return "seth_hill"; }
  Domain domain() const override { return domain_; }

 protected:
  Vec3 single(double s) const override;
  Vec3 inner(double s) const override;
  Vec3 outer(double t) const override;
  bool has_sum_term() const override { return true; }
  double single_flip(double x, double y) const override;
  double single_twist(double x, double y) const override;
  double inner_flip(double x, double y) const override;
  double inner_twist(double x, double y) const override;

 private:
  double lambda_, mu_, m_;
  Domain domain_;
};

}  // namespace sinew
