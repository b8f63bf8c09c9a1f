#include "sinew/material/families/seth_hill.hpp"

#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/material/divided_difference.hpp"

namespace sinew {

using table1::power_flip;
using table1::power_twist;
using table1::scaled_power;

SethHill::SethHill(double lambda, double mu, double m)
    : lambda_(lambda), mu_(mu), m_(m), domain_(Domain::PositiveJ) {
  if (m == 0.0 || !std::isfinite(m)) {
    throw Error(fmt::format("the Seth-Hill exponent must be a finite nonzero number, got {} "
                            "(m -> 0 is the Hencky material: use 'hencky')",
                            m),
                "parameter 'm'");
  }
  // A positive integer m makes Psi a polynomial in the signed stretches, defined for every F.
  if (m > 0.0 && m == std::round(m) && m <= 64.0) domain_ = Domain::All;
}

// a(s) = mu/m^2 (s^m - 1)^2, a' = 2 mu/m (s^(2m-1) - s^(m-1))
Vec3 SethHill::single(double s) const {
  const double m = m_, c = 2.0 * mu_ / m;
  const double e = std::pow(s, m) - 1.0;
  return {mu_ / (m * m) * e * e, c * (std::pow(s, 2.0 * m - 1.0) - std::pow(s, m - 1.0)),
          c * (scaled_power(2.0 * m - 1.0, s, 2.0 * m - 2.0) - scaled_power(m - 1.0, s, m - 2.0))};
}

// b(s) = s^m
Vec3 SethHill::inner(double s) const {
  return {std::pow(s, m_), m_ * std::pow(s, m_ - 1.0), scaled_power(m_ * (m_ - 1.0), s, m_ - 2.0)};
}

// G(t) = lambda/(2 m^2) (t - 3)^2
Vec3 SethHill::outer(double t) const {
  const double k = lambda_ / (m_ * m_);
  return {0.5 * k * (t - 3.0) * (t - 3.0), k * (t - 3.0), k};
}

double SethHill::single_flip(double x, double y) const {
  return 2.0 * mu_ / m_ * (power_flip(x, y, 2.0 * m_ - 1.0) - power_flip(x, y, m_ - 1.0));
}
double SethHill::single_twist(double x, double y) const {
  return 2.0 * mu_ / m_ * (power_twist(x, y, 2.0 * m_ - 1.0) - power_twist(x, y, m_ - 1.0));
}
double SethHill::inner_flip(double x, double y) const { return m_ * power_flip(x, y, m_ - 1.0); }
double SethHill::inner_twist(double x, double y) const { return m_ * power_twist(x, y, m_ - 1.0); }

}  // namespace sinew
