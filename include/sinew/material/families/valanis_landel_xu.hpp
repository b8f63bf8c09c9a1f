#pragma once
#include "sinew/material/expression.hpp"
#include "sinew/material/separable.hpp"

namespace sinew {

// Valanis-Landel, Xu's version (Xu et al. 2015; paper 002 Table 1) with user f, g, h:
//   Psi = sum_i f(s_i) + sum_{i<j} g(s_i s_j) + h(J),
// the g sum running over the three unordered pairs (the reading that reproduces the table's
// Lame column; see docs). Derived from the energy:
//   lambda_Lame = g''(1) + g'(1) + h''(1) + h'(1),  mu_Lame = (f''(1) + g''(1) - g'(1) - h'(1))/2,
// the table's (g'' + h'', (f'' + g'')/2) when g'(1) = h'(1) = 0. Rest stability
// f'(1) + 2 g'(1) + h'(1) = 0 is required (checked). J > 0 only.
class ValanisLandelXu final : public SeparableStretchMaterial {
 public:
  ValanisLandelXu(ScalarFunction f, ScalarFunction g, ScalarFunction h);
  std::string name() const override { return "valanis_landel_xu"; }
  Domain domain() const override { return Domain::PositiveJ; }

  double psi_stretch(const Vec3& s) const override;
  Vec3 grad_stretch(const Vec3& s) const override;
  Mat3 hess_stretch(const Vec3& s) const override;
  void pair_eigenvalues(const Vec3& s, const Vec3& p, const Mat3& h, Vec3& twist,
                        Vec3& flip) const override;

 protected:
  Vec3 single(double s) const override;
  Vec3 volume(double J) const override;

 private:
  ScalarFunction f_, g_, h_;
};

}  // namespace sinew
