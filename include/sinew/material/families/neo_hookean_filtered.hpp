#pragma once
#include <string>

#include "sinew/material/material.hpp"

namespace sinew {

// The original Neo-Hookean energy (paper 000 Eq. 5), filtered as the §6 comparison baseline:
//   Psi = mu/2 (I_C - 3) - mu log J + lambda/2 (log J)^2
//       = mu/2 sum (s_i^2 - 1) - mu L + lambda/2 L^2,   L = sum_i l(s_i),
// with log s_i replaced below the threshold c (Irving et al. 2004's sigma_f) by its
// second-order Taylor expansion at c (an energy filter in the sense of Stomakhin et al. 2012):
//   l(s) = log s                                   s >= c,
//   l(s) = log c + (s - c)/c - (s - c)^2 / (2 c^2)  s <  c.
// l is C2 at c and increasing for s < 2c, so Psi is C2 and defined for every F, and the
// principal stress d l/ds continues linearly below c, as Irving's clamped stress does. Teran
// et al. 2005's eigenvalue clamp is kept as the projection floor epsilon_p (hessian_threshold).
// Requires 0 < threshold < 1 (the rest shape is not filtered); lambda_Lame = lambda,
// mu_Lame = mu.
class NeoHookeanFiltered final : public StretchMaterial {
 public:
  NeoHookeanFiltered(double lambda, double mu, double threshold, double hessian_threshold);
  std::string name() const override { return "neo_hookean_filtered"; }
  double projection_floor() const override { return hessian_threshold_; }

  double psi_stretch(const Vec3& s) const override;
  Vec3 grad_stretch(const Vec3& s) const override;
  Mat3 hess_stretch(const Vec3& s) const override;
  // Closed-form divided differences of l' (no cancellation when s_i ~ s_j).
  void pair_eigenvalues(const Vec3& s, const Vec3& p, const Mat3& h, Vec3& twist,
                        Vec3& flip) const override;

  // The filtered logarithm and its first two derivatives.
  double log_filtered(double s) const;
  double log_filtered_d(double s) const;
  double log_filtered_dd(double s) const;

 private:
  double lambda_, mu_, c_, hessian_threshold_;
};

}  // namespace sinew
