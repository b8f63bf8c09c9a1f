#include "sinew/material/families/valanis_landel.hpp"

#include <cmath>

#include "sinew/material/divided_difference.hpp"

namespace sinew {

// a(s) = 2 mu (s (log s - 1) + 1), a' = 2 mu log s
Vec3 ValanisLandel::single(double s) const {
  const double L = std::log(s);
  // s (log s - 1) + 1 = s log s - (s - 1): no O(1) terms cancelling near s = 1.
  return {2.0 * mu_ * (s * L - (s - 1.0)), 2.0 * mu_ * L, 2.0 * mu_ / s};
}

// V(J) = lambda/2 log^2 J
Vec3 ValanisLandel::volume(double J) const {
  const double L = std::log(J);
  return {0.5 * lambda_ * L * L, lambda_ * L / J, lambda_ * (1.0 - L) / (J * J)};
}

double ValanisLandel::single_flip(double x, double y) const {
  return 2.0 * mu_ * table1::log_flip(x, y);
}

}  // namespace sinew
