#include "sinew/material/families/symmetric_arap.hpp"

#include <cmath>

#include "sinew/material/divided_difference.hpp"

namespace sinew {

using table1::power_flip;
using table1::power_twist;

// a(s) = mu/2 ((s - 1)^2 + (1 - 1/s)^2), a' = mu (s - 1 + s^-2 - s^-3)
Vec3 SymmetricArap::single(double s) const {
  const double r = 1.0 / s, e = 1.0 - r;
  return {0.5 * mu_ * ((s - 1.0) * (s - 1.0) + e * e), mu_ * (s - 1.0 + r * r - r * r * r),
          mu_ * (1.0 - 2.0 * r * r * r + 3.0 * r * r * r * r)};
}

double SymmetricArap::single_flip(double x, double y) const {
  return mu_ * (1.0 + power_flip(x, y, -2.0) - power_flip(x, y, -3.0));
}
double SymmetricArap::single_twist(double x, double y) const {
  return mu_ * (1.0 - power_twist(x, y, 0.0) + power_twist(x, y, -2.0) - power_twist(x, y, -3.0));
}

}  // namespace sinew
