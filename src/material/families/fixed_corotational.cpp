#include "sinew/material/families/fixed_corotational.hpp"

#include <algorithm>
#include <cmath>

namespace sinew {

namespace {
Vec3 stretch_cofactor(const Vec3& s) { return {s(1) * s(2), s(0) * s(2), s(0) * s(1)}; }
}  // namespace

double FixedCorotational::psi_stretch(const Vec3& s) const {
  const double v = s.prod() - 1.0;
  return mu_ * (s.array() - 1.0).square().sum() + 0.5 * lambda_ * v * v;  // Eq. 49
}

Vec3 FixedCorotational::grad_stretch(const Vec3& s) const {
  return 2.0 * mu_ * (s.array() - 1.0).matrix() + lambda_ * (s.prod() - 1.0) * stretch_cofactor(s);
}

Mat3 FixedCorotational::hess_stretch(const Vec3& s) const {
  const Vec3 g = stretch_cofactor(s);
  Mat3 volume;  // d^2 J / d sigma^2
  volume << 0.0, s(2), s(1),
            s(2), 0.0, s(0),
            s(1), s(0), 0.0;
  return 2.0 * mu_ * Mat3::Identity() + lambda_ * g * g.transpose() +
         lambda_ * (s.prod() - 1.0) * volume;
}

void FixedCorotational::pair_eigenvalues(const Vec3& s, const Vec3&, const Mat3&, Vec3& twist,
                                         Vec3& flip) const {
  // p_i = 2 mu (s_i - 1) + lambda (J - 1) s_j s_k gives
  //   (p_i - p_j)/(s_i - s_j) = 2 mu - lambda (J - 1) s_k,
  //   (p_i + p_j)/(s_i + s_j) = 2 mu - 4 mu/(s_i + s_j) + lambda (J - 1) s_k.
  // The second is singular at s_i = -s_j: R = U V^T jumps there (as in co-rotational).
  const double v = s.prod() - 1.0;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double sum = s(i) + s(j);
    const double safe = std::copysign(std::max(std::abs(sum), 1e-12), sum);
    flip(k) = 2.0 * mu_ - lambda_ * v * s(k);
    twist(k) = 2.0 * mu_ - 4.0 * mu_ / safe + lambda_ * v * s(k);
  }
}

}  // namespace sinew
