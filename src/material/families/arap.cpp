#include "sinew/material/families/arap.hpp"

#include "sinew/material/divided_difference.hpp"

namespace sinew {

// a(s) = mu (s - 1)^2, a' = 2 mu (s - 1)
Vec3 Arap::single(double s) const { return {mu_ * (s - 1.0) * (s - 1.0), 2.0 * mu_ * (s - 1.0), 2.0 * mu_}; }

double Arap::single_flip(double, double) const { return 2.0 * mu_; }

// 2 mu (x + y - 2)/(x + y): singular at y = -x, where R = U V^T jumps.
double Arap::single_twist(double x, double y) const {
  return 2.0 * mu_ * (1.0 - table1::power_twist(x, y, 0.0));
}

}  // namespace sinew
