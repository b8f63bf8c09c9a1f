#include "sinew/material/families/mooney_rivlin.hpp"

#include <cmath>

namespace sinew {

namespace {

// One term C J^q B(s): value, gradient and Hessian by the product rule, with
//   d_i J^q = q J^q / s_i,  d_ij J^q = q^2 J^q / (s_i s_j) - delta_ij q J^q / s_i^2.
struct Term {
  double C, q, B;
  Vec3 dB;
  Mat3 ddB;
};

double term_psi(const Term& t, double J) { return t.C * std::pow(J, t.q) * t.B; }

Vec3 term_grad(const Term& t, const Vec3& s, double J) {
  const double A = std::pow(J, t.q);
  const Vec3 dA = t.q * A * s.cwiseInverse();
  return t.C * (dA * t.B + A * t.dB);
}

Mat3 term_hess(const Term& t, const Vec3& s, double J) {
  const double A = std::pow(J, t.q);
  const Vec3 inv = s.cwiseInverse();
  const Vec3 dA = t.q * A * inv;
  Mat3 ddA = t.q * t.q * A * inv * inv.transpose();
  ddA.diagonal() -= t.q * A * inv.cwiseProduct(inv);
  return t.C * (ddA * t.B + dA * t.dB.transpose() + t.dB * dA.transpose() + A * t.ddB);
}

// I_1 - 3 and I_2 - 3 with their stretch derivatives:
//   d_i I_1 = 2 s_i,              d_ij I_1 = 2 delta_ij,
//   d_i I_2 = 2 s_i (I_1 - s_i^2), d_ij I_2 = 4 s_i s_j + delta_ij (2 I_1 - 6 s_i^2).
// I_1 - 3 and I_2 - 3 are formed from d_i = s_i - 1 so that they keep full accuracy near the
// rest shape (s_i s_j - 1 = d_i + d_j + d_i d_j).
double i1_minus_3(const Vec3& s) {
  const Vec3 d = s.array() - 1.0;
  return d.dot(s + Vec3::Ones());
}
double i2_minus_3(const Vec3& s) {
  const Vec3 d = s.array() - 1.0;
  double r = 0.0;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    r += (d(i) + d(j) + d(i) * d(j)) * (s(i) * s(j) + 1.0);
  }
  return r;
}

Term first(double C1, const Vec3& s) {
  return {C1, -2.0 / 3.0, i1_minus_3(s), 2.0 * s, 2.0 * Mat3::Identity()};
}
Term second(double C2, const Vec3& s) {
  const Vec3 q = s.cwiseProduct(s);
  const double I1 = q.sum();
  Mat3 dd = 4.0 * s * s.transpose();
  dd.diagonal() += (2.0 * I1 * Vec3::Ones() - 6.0 * q);
  return {C2, -4.0 / 3.0, i2_minus_3(s), 2.0 * s.cwiseProduct(I1 * Vec3::Ones() - q), dd};
}

}  // namespace

// Psi = C1 J^(-2/3) (I_1 - 3) + C2 J^(-4/3) (I_2 - 3)   (paper 002 Table 1, literal reading)
double MooneyRivlin::psi_stretch(const Vec3& s) const {
  const double J = s.prod();
  return term_psi(first(C1_, s), J) + term_psi(second(C2_, s), J);
}

Vec3 MooneyRivlin::grad_stretch(const Vec3& s) const {
  const double J = s.prod();
  return term_grad(first(C1_, s), s, J) + term_grad(second(C2_, s), s, J);
}

Mat3 MooneyRivlin::hess_stretch(const Vec3& s) const {
  const double J = s.prod();
  return term_hess(first(C1_, s), s, J) + term_hess(second(C2_, s), s, J);
}

// p_i = c/s_i + 2 C1 A1 s_i + 2 C2 A2 (I_1 s_i - s_i^3) with A1 = J^-2/3, A2 = J^-4/3 and
// c = -2/3 C1 A1 (I_1 - 3) - 4/3 C2 A2 (I_2 - 3), so for pair (i, j) and third index k:
//   flip  = -c/(s_i s_j) + 2 C1 A1 + 2 C2 A2 (s_k^2 - s_i s_j),
//   twist =  c/(s_i s_j) + 2 C1 A1 + 2 C2 A2 (s_k^2 + s_i s_j).
void MooneyRivlin::pair_eigenvalues(const Vec3& s, const Vec3&, const Mat3&, Vec3& twist,
                                    Vec3& flip) const {
  const double J = s.prod();
  const double A1 = std::pow(J, -2.0 / 3.0), A2 = std::pow(J, -4.0 / 3.0);
  const Vec3 q = s.cwiseProduct(s);
  const double c = -2.0 / 3.0 * C1_ * A1 * i1_minus_3(s) - 4.0 / 3.0 * C2_ * A2 * i2_minus_3(s);
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double sij = s(i) * s(j);
    flip(k) = -c / sij + 2.0 * C1_ * A1 + 2.0 * C2_ * A2 * (q(k) - sij);
    twist(k) = c / sij + 2.0 * C1_ * A1 + 2.0 * C2_ * A2 * (q(k) + sij);
  }
}

}  // namespace sinew
