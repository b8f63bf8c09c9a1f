#pragma once
#include "sinew/material/separable.hpp"

namespace sinew {

// Symmetric Seth-Hill (Bazant 1998; paper 002 Table 1):
//   Psi = mu/(4 m^2) sum_i (s_i^m - s_i^-m)^2 + lambda/(8 m^2) (sum_i (s_i^m - s_i^-m))^2,
// m != 0 (m and -m give the same energy). lambda_Lame = lambda, mu_Lame = mu. J > 0 only.
class SymmetricSethHill final : public SeparableStretchMaterial {
 public:
  SymmetricSethHill(double lambda, double mu, double m);  // throws sinew::Error for m == 0
  std::string name() const override { return "symmetric_seth_hill"; }
  Domain domain() const override { return Domain::PositiveJ; }

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
};

}  // namespace sinew
