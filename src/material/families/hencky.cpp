#include "sinew/material/families/hencky.hpp"

#include <cmath>

#include "sinew/material/divided_difference.hpp"

namespace sinew {

// a(s) = mu log^2 s
Vec3 Hencky::single(double s) const {
  const double L = std::log(s);
  return {mu_ * L * L, 2.0 * mu_ * L / s, 2.0 * mu_ * (1.0 - L) / (s * s)};
}

// V(J) = lambda/2 log^2 J
Vec3 Hencky::volume(double J) const {
  const double L = std::log(J);
  return {0.5 * lambda_ * L * L, lambda_ * L / J, lambda_ * (1.0 - L) / (J * J)};
}

// [2 mu log(s)/s](x, y) = 2 mu (y [log](x, y) - log y) / (x y): exact, limit 2 mu (1 - log x)/x^2.
double Hencky::single_flip(double x, double y) const {
  return 2.0 * mu_ * (y * table1::log_flip(x, y) - std::log(y)) / (x * y);
}

}  // namespace sinew
