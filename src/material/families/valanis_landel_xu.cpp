#include "sinew/material/families/valanis_landel_xu.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/material/divided_difference.hpp"

namespace sinew {

namespace {
Vec3 at_one(const ScalarFunction& fn, const char* key) {
  try {
    return fn.derivatives(1.0);
  } catch (const Error& e) {
    throw e.within(fmt::format("function '{}'", key));
  }
}
}  // namespace

ValanisLandelXu::ValanisLandelXu(ScalarFunction f, ScalarFunction g, ScalarFunction h)
    : f_(std::move(f)), g_(std::move(g)), h_(std::move(h)) {
  // Rest stability: p_i(1, 1, 1) = f'(1) + 2 g'(1) + h'(1) (each stretch is in two pairs).
  const Vec3 f1 = at_one(f_, "f"), g1 = at_one(g_, "g"), h1 = at_one(h_, "h");
  const double scale = std::max({1.0, std::abs(f1(1)), std::abs(g1(1)), std::abs(h1(1)),
                                 std::abs(f1(2)), std::abs(g1(2)), std::abs(h1(2))});
  if (std::abs(f1(1) + 2.0 * g1(1) + h1(1)) > 1e-10 * scale) {
    throw Error(fmt::format("the rest shape must be stress-free: f'(1) + 2 g'(1) + h'(1) = 0 is "
                            "required, got f'(1) = {}, g'(1) = {}, h'(1) = {} for f(x) = {}, "
                            "g(x) = {}, h(x) = {}",
                            f1(1), g1(1), h1(1), f_.text(), g_.text(), h_.text()),
                "functions 'f', 'g', 'h'");
  }
}

Vec3 ValanisLandelXu::single(double s) const { return f_.derivatives(s); }
Vec3 ValanisLandelXu::volume(double J) const { return h_.derivatives(J); }

// The pair term sum_{i<j} g(s_i s_j) on top of sum_i f(s_i) + h(J). Pair k couples
// (i, j) = ((k+1)%3, (k+2)%3).
double ValanisLandelXu::psi_stretch(const Vec3& s) const {
  double psi = SeparableStretchMaterial::psi_stretch(s);
  for (int k = 0; k < 3; ++k) psi += g_.value(s((k + 1) % 3) * s((k + 2) % 3));
  return psi;
}

// d g(s_i s_j) / d s_i = g' s_j
Vec3 ValanisLandelXu::grad_stretch(const Vec3& s) const {
  Vec3 p = SeparableStretchMaterial::grad_stretch(s);
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double dg = g_.derivatives(s(i) * s(j))(1);
    p(i) += dg * s(j);
    p(j) += dg * s(i);
  }
  return p;
}

// d^2 g(s_i s_j): g'' s_j^2 (ii), g'' s_i^2 (jj), g'' s_i s_j + g' (ij)
Mat3 ValanisLandelXu::hess_stretch(const Vec3& s) const {
  Mat3 H = SeparableStretchMaterial::hess_stretch(s);
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const Vec3 g = g_.derivatives(s(i) * s(j));
    H(i, i) += g(2) * s(j) * s(j);
    H(j, j) += g(2) * s(i) * s(i);
    const double off = g(2) * s(i) * s(j) + g(1);
    H(i, j) += off;
    H(j, i) += off;
  }
  return H;
}

// For pair (i, j) with third index k, the g-part of p_i -/+ p_j is
//   g'(s_i s_j)(s_j -/+ s_i) + s_k (g'(s_i s_k) -/+ g'(s_j s_k)), hence
//   flip  += -g'(s_i s_j) + s_k^2 [g'](s_i s_k, s_j s_k),
//   twist +=  g'(s_i s_j) + s_k (g'(s_i s_k) + g'(s_j s_k)) / (s_i + s_j).
void ValanisLandelXu::pair_eigenvalues(const Vec3& s, const Vec3& p, const Mat3& h, Vec3& twist,
                                       Vec3& flip) const {
  SeparableStretchMaterial::pair_eigenvalues(s, p, h, twist, flip);
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double gij = g_.derivatives(s(i) * s(j))(1);
    const Vec3 gi = g_.derivatives(s(i) * s(k)), gj = g_.derivatives(s(j) * s(k));
    flip(k) += -gij + s(k) * s(k) *
                          table1::flip_quotient(gi(1), gj(1), gi(2), gj(2), s(i) * s(k), s(j) * s(k));
    twist(k) += gij + s(k) * table1::twist_quotient(gi(1), gj(1), s(i), s(j));
  }
}

}  // namespace sinew
