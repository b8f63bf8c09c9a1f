#include "sinew/material/families/symmetric_dirichlet.hpp"

#include "sinew/material/divided_difference.hpp"

namespace sinew {

// a(s) = mu/2 (s - 1/s)^2, a' = mu (s - s^-3), a'' = mu (1 + 3 s^-4)
Vec3 SymmetricDirichlet::single(double s) const {
  const double r = 1.0 / s, e = s - r, r2 = r * r;
  return {0.5 * mu_ * e * e, mu_ * (s - r2 * r), mu_ * (1.0 + 3.0 * r2 * r2)};
}

double SymmetricDirichlet::single_flip(double x, double y) const {
  return mu_ * (1.0 - table1::power_flip(x, y, -3.0));
}
double SymmetricDirichlet::single_twist(double x, double y) const {
  return mu_ * (1.0 - table1::power_twist(x, y, -3.0));
}

}  // namespace sinew
