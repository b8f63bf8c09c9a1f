#pragma once
#include <string>

#include "sinew/material/families/stvk.hpp"

namespace sinew {

// StVK with Kikuuwe et al. (2009)'s compression resistance (paper 000 Eq. 51):
//   Psi = mu ||E||_F^2 + lambda/2 tr^2(E) + kappa/12 ((1 - J)/6)^3   for J < 1,
//   the last term being zero for J >= 1. (1 - J)^3 has zero value, slope and curvature at
//   J = 1, so Psi is C2 there: P and the Hessian are continuous. Rest-stable; Lamé parameters
//   as StVK's (the term vanishes to third order at rest). Defined for every F.
class StVKKikuuwe final : public StVK {
 public:
  StVKKikuuwe(double lambda, double mu, double kappa) : StVK(lambda, mu), kappa_(kappa) {}
  std::string name() const override { return "stvk_kikuuwe"; }

  double psi_stretch(const Vec3& s) const override;
  Vec3 grad_stretch(const Vec3& s) const override;
  Mat3 hess_stretch(const Vec3& s) const override;
  void pair_eigenvalues(const Vec3& s, const Vec3& p, const Mat3& h, Vec3& twist,
                        Vec3& flip) const override;

  // The compression term c(J) = kappa/12 ((1 - J)/6)^3 for J < 1, else 0, and its derivatives.
  double compression(double J) const;
  double compression_dJ(double J) const;
  double compression_dJJ(double J) const;

 private:
  double kappa_;
};

}  // namespace sinew
