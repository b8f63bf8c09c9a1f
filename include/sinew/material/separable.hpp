#pragma once
// The shape shared by most of paper 002 Table 1:
//   psi(s) = sum_i a(s_i) + G(sum_i b(s_i)) + V(J),   J = s_0 s_1 s_2,
// a per-stretch term a, a function G of a sum of per-stretch terms b (the Seth-Hill/Hill
// "lambda" part), and a volume term V. Subclasses give a, b, G, V as (value, d1, d2) and,
// where they have them, exact divided differences of a' and b'; the base assembles
//   p_i  = a'(s_i) + G'(t) b'(s_i) + V'(J) J/s_i,                                 (t = sum b)
//   H_ij = delta_ij (a''(s_i) + G'(t) b''(s_i)) + G''(t) b'(s_i) b'(s_j)
//          + V''(J) (J/s_i)(J/s_j) + V'(J) (1 - delta_ij) s_k,
// and the twist/flip eigenvalues of pair (i, j) with k the third index:
//   flip  = [a'](s_i, s_j) + G'(t) [b'](s_i, s_j) - V'(J) s_k,
//   twist = {a'}(s_i, s_j) + G'(t) {b'}(s_i, s_j) + V'(J) s_k,
// with [g](x, y) = (g(x) - g(y))/(x - y) and {g}(x, y) = (g(x) + g(y))/(x + y). The volume
// part is exact: (J/s_i - J/s_j)/(s_i - s_j) = -s_k.
#include "sinew/material/material.hpp"

namespace sinew {

class SeparableStretchMaterial : public StretchMaterial {
 public:
  double psi_stretch(const Vec3& s) const override;
  Vec3 grad_stretch(const Vec3& s) const override;
  Mat3 hess_stretch(const Vec3& s) const override;
  void pair_eigenvalues(const Vec3& s, const Vec3& p, const Mat3& h, Vec3& twist,
                        Vec3& flip) const override;

 protected:
  // (value, first, second derivative) of each part.
  virtual Vec3 single(double s) const = 0;                    // a(s)
  virtual Vec3 inner(double) const { return Vec3::Zero(); }   // b(s)
  virtual Vec3 outer(double) const { return Vec3::Zero(); }   // G(t)
  virtual Vec3 volume(double) const { return Vec3::Zero(); }  // V(J)
  virtual bool has_sum_term() const { return false; }         // G and b are used

  // Divided differences of a' and b'; the defaults use the generic quotients of
  // table1/divided_difference.hpp (twist assumes s_i + s_j is not near 0).
  virtual double single_flip(double x, double y) const;
  virtual double single_twist(double x, double y) const;
  virtual double inner_flip(double x, double y) const;
  virtual double inner_twist(double x, double y) const;
};

}  // namespace sinew
