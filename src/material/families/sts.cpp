#include "sinew/material/families/sts.hpp"

#include <cmath>

#include "sinew/material/divided_difference.hpp"

namespace sinew {

using table1::power_flip;
using table1::power_twist;

// a(s) = mu/2 (s^2 - 1) + mu4/8 (s^2 - 1)^4, a' = mu s + mu4 s (s^2 - 1)^3
Vec3 Sts::single(double s) const {
  const double e = (s - 1.0) * (s + 1.0), e2 = e * e;  // s^2 - 1 without cancellation
  return {0.5 * mu_ * e + 0.125 * mu4_ * e2 * e2, mu_ * s + mu4_ * s * e2 * e,
          mu_ + mu4_ * (e2 * e + 6.0 * s * s * e2)};
}

// V(J) = -mu log J + lambda/2 log^2 J
Vec3 Sts::volume(double J) const {
  const double L = std::log(J);
  return {-mu_ * L + 0.5 * lambda_ * L * L, (lambda_ * L - mu_) / J,
          (mu_ + lambda_ * (1.0 - L)) / (J * J)};
}

// s (s^2 - 1)^3 = s^7 - 3 s^5 + 3 s^3 - s: exact polynomial quotients.
double Sts::single_flip(double x, double y) const {
  return mu_ + mu4_ * (power_flip(x, y, 7) - 3.0 * power_flip(x, y, 5) +
                       3.0 * power_flip(x, y, 3) - 1.0);
}
double Sts::single_twist(double x, double y) const {
  return mu_ + mu4_ * (power_twist(x, y, 7) - 3.0 * power_twist(x, y, 5) +
                       3.0 * power_twist(x, y, 3) - 1.0);
}

}  // namespace sinew
