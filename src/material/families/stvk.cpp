#include "sinew/material/families/stvk.hpp"

namespace sinew {

double StVK::psi_stretch(const Vec3& s) const {
  const Vec3 e = 0.5 * (s.array().square() - 1.0).matrix();  // principal Green strains
  const double tr = e.sum();
  return mu_ * e.squaredNorm() + 0.5 * lambda_ * tr * tr;  // Eq. 50
}

Vec3 StVK::grad_stretch(const Vec3& s) const {
  const Vec3 e = 0.5 * (s.array().square() - 1.0).matrix();
  const double tr = e.sum();
  return (s.array() * (2.0 * mu_ * e.array() + lambda_ * tr)).matrix();  // F S, S = 2 mu E + lambda tr E I
}

Mat3 StVK::hess_stretch(const Vec3& s) const {
  const Vec3 e = 0.5 * (s.array().square() - 1.0).matrix();
  const double tr = e.sum();
  Mat3 h = lambda_ * s * s.transpose();
  for (int i = 0; i < 3; ++i) h(i, i) += 2.0 * mu_ * e(i) + lambda_ * tr + 2.0 * mu_ * s(i) * s(i);
  return h;
}

void StVK::pair_eigenvalues(const Vec3& s, const Vec3&, const Mat3&, Vec3& twist,
                            Vec3& flip) const {
  // p_i = s_i (mu (s_i^2 - 1) + lambda tr E): the divided differences are polynomials.
  const double tr = 0.5 * (s.squaredNorm() - 3.0);
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double sq = s(i) * s(i) + s(j) * s(j) - 1.0;
    flip(k) = mu_ * (sq + s(i) * s(j)) + lambda_ * tr;
    twist(k) = mu_ * (sq - s(i) * s(j)) + lambda_ * tr;
  }
}

}  // namespace sinew
