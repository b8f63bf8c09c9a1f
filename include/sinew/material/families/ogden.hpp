#pragma once
#include <vector>

#include "sinew/material/separable.hpp"

namespace sinew {

// Ogden (Ogden 1972; paper 002 Table 1), any number of terms:
//   Psi = sum_p mu_p / alpha_p (sum_i s_i^alpha_p - 3).
// Terms with mu_p = 0 are inactive; active terms need alpha_p != 0. No volume term:
// lambda_Lame = 0, mu_Lame = 1/2 sum_p mu_p (alpha_p - 1). P(I) = (sum_p mu_p) I, so the rest
// shape is stress-free only when sum_p mu_p = 0. Domain: all F when every active alpha_p is
// a positive integer, else J > 0.
class Ogden final : public SeparableStretchMaterial {
 public:
  Ogden(std::vector<double> mu, std::vector<double> alpha);  // throws sinew::Error if invalid
  std::string name() const override { return "ogden"; }
  Domain domain() const override { return domain_; }

 protected:
  Vec3 single(double s) const override;
  double single_flip(double x, double y) const override;
  double single_twist(double x, double y) const override;

 private:
  std::vector<double> mu_, alpha_;  // active terms only
  Domain domain_;
};

}  // namespace sinew
