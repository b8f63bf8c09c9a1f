#include "sinew/material/families/ogden.hpp"

#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/material/divided_difference.hpp"

namespace sinew {

using table1::power_flip;
using table1::power_twist;
using table1::scaled_power;

Ogden::Ogden(std::vector<double> mu, std::vector<double> alpha) : domain_(Domain::All) {
  if (mu.size() != alpha.size()) {
    throw Error(fmt::format("got {} coefficients mu_p but {} exponents alpha_p", mu.size(),
                            alpha.size()),
                "Ogden terms");
  }
  for (std::size_t p = 0; p < mu.size(); ++p) {
    if (!std::isfinite(mu[p]) || !std::isfinite(alpha[p])) {
      throw Error("must be finite", fmt::format("Ogden term {}", p + 1));
    }
    if (mu[p] == 0.0) continue;  // inactive term
    if (alpha[p] == 0.0) {
      throw Error(fmt::format("an active term (mu{} = {}) needs a nonzero exponent alpha{}", p + 1,
                              mu[p], p + 1),
                  fmt::format("parameter 'alpha{}'", p + 1));
    }
    mu_.push_back(mu[p]);
    alpha_.push_back(alpha[p]);
    // Only positive integer exponents keep Psi a polynomial in the signed stretches.
    if (!(alpha[p] > 0.0 && alpha[p] == std::round(alpha[p]) && alpha[p] <= 64.0)) {
      domain_ = Domain::PositiveJ;
    }
  }
}

// a(s) = sum_p mu_p/alpha_p (s^alpha_p - 1), a' = sum_p mu_p s^(alpha_p - 1)
Vec3 Ogden::single(double s) const {
  Vec3 a = Vec3::Zero();
  for (std::size_t p = 0; p < mu_.size(); ++p) {
    const double m = mu_[p], al = alpha_[p];
    a(0) += m / al * (std::pow(s, al) - 1.0);
    a(1) += m * std::pow(s, al - 1.0);
    a(2) += scaled_power(m * (al - 1.0), s, al - 2.0);
  }
  return a;
}

double Ogden::single_flip(double x, double y) const {
  double r = 0.0;
  for (std::size_t p = 0; p < mu_.size(); ++p) r += mu_[p] * power_flip(x, y, alpha_[p] - 1.0);
  return r;
}
double Ogden::single_twist(double x, double y) const {
  double r = 0.0;
  for (std::size_t p = 0; p < mu_.size(); ++p) r += mu_[p] * power_twist(x, y, alpha_[p] - 1.0);
  return r;
}

}  // namespace sinew
