#pragma once
#include "sinew/material/expression.hpp"
#include "sinew/material/separable.hpp"

namespace sinew {

// Hill family (Hill 1968; paper 002 Table 1) with a user strain measure f:
//   Psi = mu sum_i f(s_i)^2 + lambda/2 (sum_i f(s_i))^2.
// Hill's conditions f(1) = 0, f'(1) = 1 are required (checked): they make the rest shape
// stress-free and give lambda_Lame = lambda, mu_Lame = mu. f = log x is Hencky. J > 0 only.
class Hill final : public SeparableStretchMaterial {
 public:
  Hill(double lambda, double mu, ScalarFunction f);  // throws sinew::Error if f violates them
  std::string name() const override { return "hill"; }
  Domain domain() const override { return Domain::PositiveJ; }

 protected:
  Vec3 single(double s) const override;
  Vec3 inner(double s) const override;
  Vec3 outer(double t) const override;
  bool has_sum_term() const override { return true; }

 private:
  double lambda_, mu_;
  ScalarFunction f_;
};

}  // namespace sinew
