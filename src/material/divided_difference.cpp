#include "sinew/material/divided_difference.hpp"

#include <algorithm>
#include <cmath>

namespace sinew::table1 {
namespace {

// Below this relative gap a plain quotient loses more digits to cancellation than the
// midpoint limit loses to truncation (same balance as Material::pair_eigenvalues).
constexpr double kGap = 6e-6;

bool small_integer(double n) { return n == std::round(n) && std::abs(n) <= 64.0; }

// sum_{k=0}^{n-1} x^(n-1-k) y^k for an integer n >= 1 (Horner in x).
double geometric_sum(double x, double y, int n) {
  double r = 1.0, yk = 1.0;
  for (int k = 1; k < n; ++k) {
    yk *= y;
    r = r * x + yk;
  }
  return r;
}

double guarded(double sum) { return std::copysign(std::max(std::abs(sum), 1e-12), sum); }

}  // namespace

double scaled_power(double c, double s, double n) { return c == 0.0 ? 0.0 : c * std::pow(s, n); }

double power_flip(double x, double y, double n) {
  if (small_integer(n)) {
    const int k = static_cast<int>(std::round(n));
    if (k == 0) return 0.0;
    if (k > 0) return geometric_sum(x, y, k);
    // x^-k - y^-k = -(x^k - y^k) / (x^k y^k)
    return -geometric_sum(x, y, -k) / (std::pow(x, -k) * std::pow(y, -k));
  }
  if (x == y) return n * std::pow(y, n - 1.0);
  // x^n - y^n = y^n (e^(n u) - 1) with u = log(x / y), both factors to full relative accuracy.
  const double u = std::log1p((x - y) / y);
  return std::pow(y, n) * std::expm1(n * u) / (x - y);
}

double power_twist(double x, double y, double n) {
  if (small_integer(n)) {
    const int k = static_cast<int>(std::round(n));
    if (k % 2 != 0) {
      // Odd k: (x^k + y^k) / (x + y) = (x^k - (-y)^k) / (x - (-y)).
      if (k > 0) return geometric_sum(x, -y, k);
      return geometric_sum(x, -y, -k) / (std::pow(x, -k) * std::pow(y, -k));
    }
  }
  return (std::pow(x, n) + std::pow(y, n)) / guarded(x + y);
}

double log_flip(double x, double y) {
  if (x == y) return 1.0 / y;
  return std::log1p((x - y) / y) / (x - y);
}

double flip_quotient(double gx, double gy, double dgx, double dgy, double x, double y) {
  const double diff = x - y;
  if (std::abs(diff) > kGap * (std::abs(x) + std::abs(y))) return (gx - gy) / diff;
  return 0.5 * (dgx + dgy);
}

double twist_quotient(double gx, double gy, double x, double y) { return (gx + gy) / guarded(x + y); }

}  // namespace sinew::table1
