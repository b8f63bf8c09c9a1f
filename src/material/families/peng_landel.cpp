#include "sinew/material/families/peng_landel.hpp"

#include <cmath>

namespace sinew {

// a(s) = E (s - 1 - L - L^2/6 + L^3/18 - L^4/216), L = log s. With
// q(L) = 1 + L/3 - L^2/6 + L^3/54:  a' = E (1 - q/s),  a'' = E (q - q')/s^2
//                                        = E (2/3 + 2L/3 - 2L^2/9 + L^3/54)/s^2.
Vec3 PengLandel::single(double s) const {
  const double L = std::log(s), L2 = L * L, L3 = L2 * L;
  const double a = s - 1.0 - L - L2 / 6.0 + L3 / 18.0 - L2 * L2 / 216.0;
  const double q = 1.0 + L / 3.0 - L2 / 6.0 + L3 / 54.0;
  const double r = 2.0 / 3.0 + 2.0 * L / 3.0 - 2.0 * L2 / 9.0 + L3 / 54.0;
  return {E_ * a, E_ * (1.0 - q / s), E_ * r / (s * s)};
}

}  // namespace sinew
