#include "sinew/material/families/hill.hpp"

#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

Hill::Hill(double lambda, double mu, ScalarFunction f) : lambda_(lambda), mu_(mu), f_(std::move(f)) {
  // Hill's conditions on the strain measure: f(1) = 0 (no energy and, with the next one, no
  // stress at rest) and f'(1) = 1 (the Lame parameters are lambda, mu; in general they are
  // f'(1)^2 lambda and f'(1)^2 mu).
  Vec3 f1;
  try {
    f1 = f_.derivatives(1.0);
  } catch (const Error& e) {
    throw e.within("function 'f'");
  }
  constexpr double kTol = 1e-10;
  if (std::abs(f1(0)) > kTol || std::abs(f1(1) - 1.0) > kTol) {
    throw Error(fmt::format("Hill's strain measure must satisfy f(1) = 0 and f'(1) = 1, got "
                            "f(1) = {}, f'(1) = {} for f(x) = {}",
                            f1(0), f1(1), f_.text()),
                "function 'f'");
  }
}

// a(s) = mu f(s)^2
Vec3 Hill::single(double s) const {
  const Vec3 f = f_.derivatives(s);
  return {mu_ * f(0) * f(0), 2.0 * mu_ * f(0) * f(1), 2.0 * mu_ * (f(1) * f(1) + f(0) * f(2))};
}

// b(s) = f(s)
Vec3 Hill::inner(double s) const { return f_.derivatives(s); }

// G(t) = lambda/2 t^2
Vec3 Hill::outer(double t) const { return {0.5 * lambda_ * t * t, lambda_ * t, lambda_}; }

}  // namespace sinew
