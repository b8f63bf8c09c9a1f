#include "sinew/material/families/symmetric_seth_hill.hpp"

#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/material/divided_difference.hpp"

namespace sinew {

using table1::power_flip;
using table1::power_twist;
using table1::scaled_power;

SymmetricSethHill::SymmetricSethHill(double lambda, double mu, double m)
    : lambda_(lambda), mu_(mu), m_(m) {
  if (m == 0.0 || !std::isfinite(m)) {
    throw Error(fmt::format("the symmetric Seth-Hill exponent must be a finite nonzero number, "
                            "got {}",
                            m),
                "parameter 'm'");
  }
}

// a(s) = mu/(4 m^2) (s^m - s^-m)^2, a' = mu/(2m) (s^(2m-1) - s^(-2m-1))
Vec3 SymmetricSethHill::single(double s) const {
  const double m = m_, c = 0.5 * mu_ / m;
  const double e = std::pow(s, m) - std::pow(s, -m);
  return {0.25 * mu_ / (m * m) * e * e,
          c * (std::pow(s, 2.0 * m - 1.0) - std::pow(s, -2.0 * m - 1.0)),
          c * (scaled_power(2.0 * m - 1.0, s, 2.0 * m - 2.0) +
               (2.0 * m + 1.0) * std::pow(s, -2.0 * m - 2.0))};
}

// b(s) = s^m - s^-m
Vec3 SymmetricSethHill::inner(double s) const {
  const double m = m_;
  return {std::pow(s, m) - std::pow(s, -m), m * (std::pow(s, m - 1.0) + std::pow(s, -m - 1.0)),
          m * (scaled_power(m - 1.0, s, m - 2.0) - scaled_power(m + 1.0, s, -m - 2.0))};
}

// G(t) = lambda/(8 m^2) t^2
Vec3 SymmetricSethHill::outer(double t) const {
  const double k = 0.25 * lambda_ / (m_ * m_);
  return {0.5 * k * t * t, k * t, k};
}

double SymmetricSethHill::single_flip(double x, double y) const {
  return 0.5 * mu_ / m_ * (power_flip(x, y, 2.0 * m_ - 1.0) - power_flip(x, y, -2.0 * m_ - 1.0));
}
double SymmetricSethHill::single_twist(double x, double y) const {
  return 0.5 * mu_ / m_ * (power_twist(x, y, 2.0 * m_ - 1.0) - power_twist(x, y, -2.0 * m_ - 1.0));
}
double SymmetricSethHill::inner_flip(double x, double y) const {
  return m_ * (power_flip(x, y, m_ - 1.0) + power_flip(x, y, -m_ - 1.0));
}
double SymmetricSethHill::inner_twist(double x, double y) const {
  return m_ * (power_twist(x, y, m_ - 1.0) + power_twist(x, y, -m_ - 1.0));
}

}  // namespace sinew
