#pragma once
// The nonlinearity exponent (paper 002 §5): any isotropic energy psi becomes
//   psi_alpha(s) = psi(s_0^alpha, s_1^alpha, s_2^alpha) / alpha^2            (Eq. 16)
// with the same stretch Hessian at the rest shape (Eq. 18 at s = 1), hence the same Lamé
// parameters, E and nu; alpha < 1 softens, alpha > 1 stiffens under large deformation.
// Applied to linear corotational it gives the Seth-Hill family (alpha = 2: StVK).
#include <memory>

#include "sinew/material/material.hpp"

namespace sinew {

class NonlinearMaterial final : public StretchMaterial {
 public:
  // alpha > 0 and finite (sinew::Error otherwise). For alpha != 1 the energy needs s^alpha,
  // so it is defined for J > 0 only; alpha = 1 keeps the base's domain.
  NonlinearMaterial(std::shared_ptr<const Material> base, double alpha);

  std::string name() const override;
  Domain domain() const override;
  double projection_floor() const override { return base_->projection_floor(); }

  double alpha() const { return alpha_; }
  const Material& base() const { return *base_; }

  double psi_stretch(const Vec3& s) const override;
  Vec3 grad_stretch(const Vec3& s) const override;  // Eq. 17
  Mat3 hess_stretch(const Vec3& s) const override;  // Eq. 18
  // Exact divided differences of Eq. 17, written through the base's own pair eigenvalues at
  // s^alpha and divided differences of powers, so equal stretches need no limit switch.
  void pair_eigenvalues(const Vec3& s, const Vec3& p, const Mat3& h, Vec3& twist,
                        Vec3& flip) const override;

 protected:
  // alpha = 1 forwards the F view to the base (keeping its closed forms); otherwise one SVD
  // and one base evaluation at s^alpha serve the whole eigensystem.
  double psi_impl(const Mat3& F) const override;
  Mat3 pk1_impl(const Mat3& F) const override;
  Mat9 hessian_impl(const Mat3& F) const override;
  Eigensystem eigensystem_impl(const Mat3& F) const override;
  Evaluation evaluate_impl(const Mat3& F, Projection mode) const override;

 private:
  struct Stretch;  // everything at one s: s^alpha, base derivatives there, wrapper derivatives
  Stretch at(const Vec3& s) const;
  void pairs(const Stretch& st, Vec3& twist, Vec3& flip) const;
  Eigensystem eigensystem_from(const SignedSvd& svd, const Stretch& st) const;

  std::shared_ptr<const Material> base_;
  double alpha_;
};

// (x^beta - y^beta) / (x - y) for x, y > 0, accurate also when x and y (nearly) coincide
// (limit beta x^(beta - 1)).
double power_divided_difference(double x, double y, double beta);

}  // namespace sinew
