#pragma once
#include "sinew/material/expression.hpp"
#include "sinew/material/separable.hpp"

namespace sinew {

// Valanis-Landel, "new" form (Valanis 2022, Chen et al. 2023; paper 002 Table 1) with user
// functions f and h:
//   Psi = sum_i f(s_i) + h(J).
// Derived from the energy: lambda_Lame = h''(1) + h'(1), mu_Lame = (f''(1) - h'(1))/2, which is
// the table's (h''(1), f''(1)/2) when h'(1) = 0. Rest stability f'(1) + h'(1) = 0 is required
// (checked). J > 0 only.
class ValanisLandelNew final : public SeparableStretchMaterial {
 public:
  ValanisLandelNew(ScalarFunction f, ScalarFunction h);  // throws sinew::Error if not rest-stable
  std::string name() const override { return "valanis_landel_new"; }
  Domain domain() const override { return Domain::PositiveJ; }

 protected:
  Vec3 single(double s) const override;
  Vec3 volume(double J) const override;

 private:
  ScalarFunction f_, h_;
};

}  // namespace sinew
