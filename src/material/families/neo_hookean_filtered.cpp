#include "sinew/material/families/neo_hookean_filtered.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

NeoHookeanFiltered::NeoHookeanFiltered(double lambda, double mu, double threshold,
                                       double hessian_threshold)
    : lambda_(lambda), mu_(mu), c_(threshold), hessian_threshold_(hessian_threshold) {
  if (!(threshold > 0.0) || !(threshold < 1.0)) {
    throw Error(fmt::format("must satisfy 0 < threshold < 1 (log is filtered below it, and the "
                            "rest shape must stay unfiltered), got {}",
                            threshold),
                "threshold");
  }
}

double NeoHookeanFiltered::log_filtered(double s) const {
  if (s >= c_) return std::log(s);
  const double d = (s - c_) / c_;
  return std::log(c_) + d - 0.5 * d * d;  // second-order Taylor expansion of log at c
}
double NeoHookeanFiltered::log_filtered_d(double s) const {
  return s >= c_ ? 1.0 / s : (2.0 * c_ - s) / (c_ * c_);
}
double NeoHookeanFiltered::log_filtered_dd(double s) const {
  return s >= c_ ? -1.0 / (s * s) : -1.0 / (c_ * c_);
}

double NeoHookeanFiltered::psi_stretch(const Vec3& s) const {
  const double L = log_filtered(s(0)) + log_filtered(s(1)) + log_filtered(s(2));  // ~ log J
  return 0.5 * mu_ * (s.squaredNorm() - 3.0) - mu_ * L + 0.5 * lambda_ * L * L;  // Eq. 5
}

Vec3 NeoHookeanFiltered::grad_stretch(const Vec3& s) const {
  const double L = log_filtered(s(0)) + log_filtered(s(1)) + log_filtered(s(2));
  Vec3 p;
  for (int i = 0; i < 3; ++i) p(i) = mu_ * s(i) + (lambda_ * L - mu_) * log_filtered_d(s(i));
  return p;
}

Mat3 NeoHookeanFiltered::hess_stretch(const Vec3& s) const {
  const double L = log_filtered(s(0)) + log_filtered(s(1)) + log_filtered(s(2));
  const Vec3 d(log_filtered_d(s(0)), log_filtered_d(s(1)), log_filtered_d(s(2)));
  Mat3 h = lambda_ * d * d.transpose();
  for (int i = 0; i < 3; ++i) h(i, i) += mu_ + (lambda_ * L - mu_) * log_filtered_dd(s(i));
  return h;
}

void NeoHookeanFiltered::pair_eigenvalues(const Vec3& s, const Vec3&, const Mat3&, Vec3& twist,
                                          Vec3& flip) const {
  // p_i = mu s_i + (lambda L - mu) l'(s_i), so
  //   flip  = mu + (lambda L - mu) (l'(s_i) - l'(s_j)) / (s_i - s_j),
  //   twist = mu + (lambda L - mu) (l'(s_i) + l'(s_j)) / (s_i + s_j).
  const double L = log_filtered(s(0)) + log_filtered(s(1)) + log_filtered(s(2));
  const double k = lambda_ * L - mu_;
  const double c2 = c_ * c_;
  for (int m = 0; m < 3; ++m) {
    const double a = std::max(s((m + 1) % 3), s((m + 2) % 3));
    const double b = std::min(s((m + 1) % 3), s((m + 2) % 3));
    double minus;  // divided difference of l', written without cancellation
    if (b >= c_) {
      minus = -1.0 / (a * b);
    } else if (a < c_) {
      minus = -1.0 / c2;
    } else {  // b < c <= a: a weighted mean of the two branches' slopes
      const double A = a - c_, B = c_ - b;
      minus = -(A / (c_ * a) + B / c2) / (A + B);
    }
    double plus;
    if (b >= c_) {
      plus = 1.0 / (a * b);
    } else {
      // Singular only where s_i = -s_j, i.e. an inverted F whose two smallest |sigma| tie: the
      // filtered energy depends on the reflection convention and has a kink there.
      const double sum = a + b;
      plus = (log_filtered_d(a) + log_filtered_d(b)) /
             std::copysign(std::max(std::abs(sum), 1e-12), sum);
    }
    flip(m) = mu_ + k * minus;
    twist(m) = mu_ + k * plus;
  }
}

}  // namespace sinew
