#include "sinew/material/families/stvk_kikuuwe.hpp"

namespace sinew {

namespace {
Vec3 stretch_cofactor(const Vec3& s) { return {s(1) * s(2), s(0) * s(2), s(0) * s(1)}; }
// kappa/12 ((1 - J)/6)^3 = kappa (1 - J)^3 / 2592 (Eq. 51).
constexpr double kScale = 1.0 / (12.0 * 216.0);
}  // namespace

double StVKKikuuwe::compression(double J) const {
  if (J >= 1.0) return 0.0;  // switched off in extension
  const double d = 1.0 - J;
  return kappa_ * kScale * d * d * d;
}
double StVKKikuuwe::compression_dJ(double J) const {
  if (J >= 1.0) return 0.0;
  const double d = 1.0 - J;
  return -3.0 * kappa_ * kScale * d * d;
}
double StVKKikuuwe::compression_dJJ(double J) const {
  if (J >= 1.0) return 0.0;
  return 6.0 * kappa_ * kScale * (1.0 - J);
}

double StVKKikuuwe::psi_stretch(const Vec3& s) const {
  return StVK::psi_stretch(s) + compression(s.prod());
}

Vec3 StVKKikuuwe::grad_stretch(const Vec3& s) const {
  return StVK::grad_stretch(s) + compression_dJ(s.prod()) * stretch_cofactor(s);
}

Mat3 StVKKikuuwe::hess_stretch(const Vec3& s) const {
  const double J = s.prod();
  const Vec3 g = stretch_cofactor(s);
  Mat3 volume;  // d^2 J / d sigma^2
  volume << 0.0, s(2), s(1),
            s(2), 0.0, s(0),
            s(1), s(0), 0.0;
  return StVK::hess_stretch(s) + compression_dJJ(J) * g * g.transpose() +
         compression_dJ(J) * volume;
}

void StVKKikuuwe::pair_eigenvalues(const Vec3& s, const Vec3& p, const Mat3& h, Vec3& twist,
                                   Vec3& flip) const {
  // A function of J adds c'(J) s_k to the twist and -c'(J) s_k to the flip value.
  StVK::pair_eigenvalues(s, p, h, twist, flip);
  const double cJ = compression_dJ(s.prod());
  twist += cJ * s;
  flip -= cJ * s;
}

}  // namespace sinew
