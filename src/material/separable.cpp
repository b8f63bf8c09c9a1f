#include "sinew/material/separable.hpp"

#include "sinew/material/divided_difference.hpp"

namespace sinew {
namespace {
Vec3 cofactor_of(const Vec3& s) { return {s(1) * s(2), s(0) * s(2), s(0) * s(1)}; }
}  // namespace

double SeparableStretchMaterial::psi_stretch(const Vec3& s) const {
  double psi = 0.0, t = 0.0;
  for (int i = 0; i < 3; ++i) {
    psi += single(s(i))(0);
    if (has_sum_term()) t += inner(s(i))(0);
  }
  if (has_sum_term()) psi += outer(t)(0);
  return psi + volume(s.prod())(0);
}

Vec3 SeparableStretchMaterial::grad_stretch(const Vec3& s) const {
  Vec3 p;
  double t = 0.0;
  Vec3 db = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    p(i) = single(s(i))(1);
    if (has_sum_term()) {
      const Vec3 b = inner(s(i));
      t += b(0);
      db(i) = b(1);
    }
  }
  if (has_sum_term()) p += outer(t)(1) * db;
  return p + volume(s.prod())(1) * cofactor_of(s);
}

Mat3 SeparableStretchMaterial::hess_stretch(const Vec3& s) const {
  Mat3 H = Mat3::Zero();
  double t = 0.0;
  Vec3 db = Vec3::Zero(), ddb = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    H(i, i) = single(s(i))(2);
    if (has_sum_term()) {
      const Vec3 b = inner(s(i));
      t += b(0);
      db(i) = b(1);
      ddb(i) = b(2);
    }
  }
  if (has_sum_term()) {
    const Vec3 G = outer(t);
    H += G(2) * db * db.transpose();
    H.diagonal() += G(1) * ddb;
  }
  const Vec3 V = volume(s.prod());
  const Vec3 g = cofactor_of(s);
  Mat3 dJ2;  // d^2 J / d s^2
  dJ2 << 0.0, s(2), s(1),
         s(2), 0.0, s(0),
         s(1), s(0), 0.0;
  return H + V(2) * g * g.transpose() + V(1) * dJ2;
}

void SeparableStretchMaterial::pair_eigenvalues(const Vec3& s, const Vec3&, const Mat3&,
                                                Vec3& twist, Vec3& flip) const {
  double dG = 0.0;
  if (has_sum_term()) {
    double t = 0.0;
    for (int i = 0; i < 3; ++i) t += inner(s(i))(0);
    dG = outer(t)(1);
  }
  const double dV = volume(s.prod())(1);
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    flip(k) = single_flip(s(i), s(j)) - dV * s(k);
    twist(k) = single_twist(s(i), s(j)) + dV * s(k);
    if (has_sum_term()) {
      flip(k) += dG * inner_flip(s(i), s(j));
      twist(k) += dG * inner_twist(s(i), s(j));
    }
  }
}

double SeparableStretchMaterial::single_flip(double x, double y) const {
  const Vec3 ax = single(x), ay = single(y);
  return table1::flip_quotient(ax(1), ay(1), ax(2), ay(2), x, y);
}
double SeparableStretchMaterial::single_twist(double x, double y) const {
  return table1::twist_quotient(single(x)(1), single(y)(1), x, y);
}
double SeparableStretchMaterial::inner_flip(double x, double y) const {
  const Vec3 bx = inner(x), by = inner(y);
  return table1::flip_quotient(bx(1), by(1), bx(2), by(2), x, y);
}
double SeparableStretchMaterial::inner_twist(double x, double y) const {
  return table1::twist_quotient(inner(x)(1), inner(y)(1), x, y);
}

}  // namespace sinew
