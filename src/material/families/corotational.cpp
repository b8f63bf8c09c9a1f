#include "sinew/material/families/corotational.hpp"

#include <algorithm>
#include <cmath>

namespace sinew {

double LinearCorotational::psi_stretch(const Vec3& s) const {
  const double tr = s.sum() - 3.0;
  return mu_ * (s.array() - 1.0).square().sum() + 0.5 * lambda_ * tr * tr;
}

Vec3 LinearCorotational::grad_stretch(const Vec3& s) const {
  const double tr = s.sum() - 3.0;
  return 2.0 * mu_ * (s.array() - 1.0).matrix() + Vec3::Constant(lambda_ * tr);
}

Mat3 LinearCorotational::hess_stretch(const Vec3&) const {
  return 2.0 * mu_ * Mat3::Identity() + Mat3::Constant(lambda_);
}

void LinearCorotational::pair_eigenvalues(const Vec3& s, const Vec3&, const Mat3&, Vec3& twist,
                                          Vec3& flip) const {
  // p_i = 2 mu (s_i - 1) + lambda t with t = tr(S - I):
  //   (p_i - p_j)/(s_i - s_j) = 2 mu,  (p_i + p_j)/(s_i + s_j) = 2 mu + 2 (lambda t - 2 mu)/(s_i + s_j).
  // The twist quotient is singular at s_i = -s_j: the energy's rotation R = U V^T jumps there.
  const double t = s.sum() - 3.0;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    flip(k) = 2.0 * mu_;
    const double sum = s(i) + s(j);
    const double safe = std::copysign(std::max(std::abs(sum), 1e-12), sum);
    twist(k) = 2.0 * mu_ + 2.0 * (lambda_ * t - 2.0 * mu_) / safe;
  }
}

}  // namespace sinew
