#pragma once
#include "sinew/material/separable.hpp"

namespace sinew {

// Peng-Landel (Peng and Landel 1972; paper 002 Table 1), with L_i = log s_i:
//   Psi = E sum_i (s_i - 1 - L_i - L_i^2/6 + L_i^3/18 - L_i^4/216).
// No volume term: lambda_Lame = 0, mu_Lame = E/3. J > 0 only.
class PengLandel final : public SeparableStretchMaterial {
 public:
  explicit PengLandel(double E) : E_(E) {}
  std::string name() const override { return "peng_landel"; }
  Domain domain() const override { return Domain::PositiveJ; }

 protected:
  Vec3 single(double s) const override;

 private:
  double E_;
};

}  // namespace sinew
