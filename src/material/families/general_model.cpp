#include "sinew/material/families/general_model.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace sinew {

namespace {

Vec3 stretch_cofactor(const Vec3& s) { return {s(1) * s(2), s(0) * s(2), s(0) * s(1)}; }

Mat3 stretch_volume_hessian(const Vec3& s) {  // d^2 J / d sigma^2
  Mat3 h;
  h << 0.0, s(2), s(1),
       s(2), 0.0, s(0),
       s(1), s(0), 0.0;
  return h;
}

// Real roots of x^3 + a2 x^2 + a1 x + a0 (three real roots: the characteristic polynomial of a
// symmetric matrix), ascending, by the trigonometric method.
Vec3 real_cubic_roots(double a0, double a1, double a2) {
  const double shift = -a2 / 3.0;
  const double p = a1 - a2 * a2 / 3.0;
  const double q = a0 - a2 * a1 / 3.0 + 2.0 * a2 * a2 * a2 / 27.0;
  Vec3 t;
  if (p >= 0.0) {
    // Only a triple root has p = 0; p > 0 is rounding of a (near-)triple root.
    t.setConstant(std::cbrt(-q));
  } else {
    const double r = std::sqrt(-p / 3.0);
    const double r3 = r * r * r;  // 0 only if -p underflows: then the root is triple anyway
    const double c = r3 > 0.0 ? std::clamp(-q / (2.0 * r3), -1.0, 1.0) : 0.0;
    const double theta = std::acos(c) / 3.0;
    const double third = 2.0 * std::numbers::pi / 3.0;
    for (int k = 0; k < 3; ++k) t(k) = 2.0 * r * std::cos(theta - third * k);
  }
  Vec3 x = t.array() + shift;
  std::sort(x.data(), x.data() + 3);
  return x;
}

// Unit null vector of a symmetric 3x3 N of rank two: the longest cross product of two rows
// (each is orthogonal to the row space). Rank < 2 (a triple root, N ~ 0): any vector
// orthogonal to the longest row is a null vector.
Vec3 null_vector(const Mat3& N) {
  const Vec3 r0 = N.row(0).transpose(), r1 = N.row(1).transpose(), r2 = N.row(2).transpose();
  const Vec3 c[3] = {r0.cross(r1), r0.cross(r2), r1.cross(r2)};
  int best = 0;
  for (int k = 1; k < 3; ++k) {
    if (c[k].squaredNorm() > c[best].squaredNorm()) best = k;
  }
  const double scale = N.squaredNorm();
  if (c[best].squaredNorm() > 1e-28 * scale * scale && scale > 0.0) return c[best].normalized();
  int row = 0;
  for (int k = 1; k < 3; ++k) {
    if (N.row(k).squaredNorm() > N.row(row).squaredNorm()) row = k;
  }
  if (N.row(row).squaredNorm() == 0.0) return Vec3::UnitX();
  return N.row(row).transpose().unitOrthogonal();
}

// adj(N) x = det(N) N^{-1} x for symmetric N: the adjugate's columns are cross products of rows.
Vec3 adjugate_times(const Mat3& N, const Vec3& x) {
  const Vec3 r0 = N.row(0).transpose(), r1 = N.row(1).transpose(), r2 = N.row(2).transpose();
  return x(0) * r1.cross(r2) + x(1) * r2.cross(r0) + x(2) * r0.cross(r1);
}

}  // namespace

Vec3 general_model_cubic(const Vec3& s, const GeneralModelCoefficients& c) {
  // Eq. 43 (re-derived; the extracted text is garbled):
  //   c2 = -(|g|^2 rho + I_C eta)
  //   c1 = -(1 + 2 J rho) I_C - 6 J eta + (|g|^2 I_C - 9 J^2) rho eta
  //   c0 = -(2 + 3 J rho) J + (I_C^2 - 4 |g|^2) eta + 2 J (I_C^2 - 3 |g|^2) rho eta
  // times gamma_H^(3-k), with eta gamma_H = gamma_F and rho gamma_H = gamma_G.
  const double Ic = s.squaredNorm();
  const double J = s.prod();
  const double g2 = stretch_cofactor(s).squaredNorm();
  const double F = c.gamma_F, G = c.gamma_G, H = c.gamma_H;
  const double a2 = -(g2 * G + Ic * F);
  const double a1 = -(H * H + 2.0 * J * G * H) * Ic - 6.0 * J * F * H + (g2 * Ic - 9.0 * J * J) * G * F;
  const double a0 = -(2.0 * H * H + 3.0 * J * G * H) * J * H + (Ic * Ic - 4.0 * g2) * F * H * H +
                    2.0 * J * (Ic * Ic - 3.0 * g2) * G * F * H;
  return {a0, a1, a2};
}

ScalingBlock general_model_scaling_block(const Vec3& s, const GeneralModelCoefficients& c) {
  const Vec3 g = stretch_cofactor(s);
  // The rank-two update of gamma_H Hd; gamma_I I only shifts its eigenvalues (§4.6).
  Mat3 M = c.gamma_F * s * s.transpose() + c.gamma_G * g * g.transpose() +
           c.gamma_H * stretch_volume_hessian(s);
  ScalingBlock out;
  const double scale = M.cwiseAbs().maxCoeff();
  if (!(scale > 0.0)) {  // F = 0 or all coefficients zero: the block is gamma_I I
    out.values.setConstant(c.gamma_I);
    out.vectors.setIdentity();
    return out;
  }
  // Work with M / scale (same eigenvectors) so the cubic's coefficients stay O(1).
  M /= scale;
  const GeneralModelCoefficients unit{0.0, c.gamma_F / scale, c.gamma_G / scale, c.gamma_H / scale};
  const Vec3 a = general_model_cubic(s, unit);
  const Vec3 roots = real_cubic_roots(a(0), a(1), a(2));

  // The root farthest from the other two has the best-conditioned eigenvector: take it as the
  // longest cross product of two rows of M - eps I (a column of the adjugate, i.e. one step of
  // inverse iteration). The cubic's coefficients keep the eigenvalues' mean, so clustered roots
  // lose digits; Rayleigh quotient iteration (v <- adj(M - eps I) v, eps <- v.M v) restores them
  // and converges cubically.
  const int isolated = roots(1) - roots(0) > roots(2) - roots(1) ? 0 : 2;
  Vec3 v = null_vector(M - roots(isolated) * Mat3::Identity());
  double e = v.dot(M * v);
  for (int iteration = 0; iteration < 10; ++iteration) {
    const Mat3 N = M - e * Mat3::Identity();
    const Vec3 next_v = adjugate_times(N, v);
    const double length = next_v.norm();
    if (!(length > 0.0) || !std::isfinite(length)) {  // rank(N) <= 1: e is a repeated root
      v = null_vector(N);
      e = v.dot(M * v);
      break;
    }
    v = next_v / length;
    const double next = v.dot(M * v);
    const bool converged = std::abs(next - e) <= 1e-15;  // M is scaled to max |entry| = 1
    e = next;
    if (converged) break;
  }

  // The other two span the plane orthogonal to v: diagonalise M there with one Jacobi rotation,
  // which stays exact when their eigenvalues coincide (rest shape, sigma_i = sigma_j).
  const Vec3 u = v.unitOrthogonal();
  const Vec3 w = v.cross(u);
  const double muu = u.dot(M * u), muw = u.dot(M * w), mww = w.dot(M * w);
  double e1 = muu, e2 = mww;
  Vec3 x1 = u, x2 = w;
  if (muw != 0.0) {
    const double tau = (mww - muu) / (2.0 * muw);
    const double t = std::abs(tau) > 1e150
                         ? 0.5 / tau
                         : std::copysign(1.0, tau) / (std::abs(tau) + std::sqrt(1.0 + tau * tau));
    const double cs = 1.0 / std::sqrt(1.0 + t * t), sn = t * cs;
    e1 = muu - t * muw;
    e2 = mww + t * muw;
    x1 = cs * u - sn * w;
    x2 = sn * u + cs * w;
  }

  std::pair<double, Vec3> pairs[3] = {{e, v}, {e1, x1}, {e2, x2}};
  std::sort(std::begin(pairs), std::end(pairs),
            [](const auto& l, const auto& r) { return l.first < r.first; });
  for (int k = 0; k < 3; ++k) {
    out.values(k) = c.gamma_I + scale * pairs[k].first;  // Eq. 45: eps = gamma_H eps_bar + mu_T
    out.vectors.col(k) = pairs[k].second;
  }
  return out;
}

Eigensystem general_model_eigensystem(const SignedSvd& svd, const GeneralModelCoefficients& c) {
  const ScalingBlock block = general_model_scaling_block(svd.sigma, c);
  Eigensystem es;
  es.values.head<3>() = block.values;
  for (int k = 0; k < 3; ++k) {
    es.values(3 + k) = c.gamma_I + c.gamma_H * svd.sigma(k);  // Eq. 46-48, twist (D_3..D_5)
    es.values(6 + k) = c.gamma_I - c.gamma_H * svd.sigma(k);  // flip (D_6..D_8)
  }
  es.vectors = isotropic_eigenvectors(svd, block.vectors);
  return es;
}

InvariantMaterial::Derivatives GeneralModelMaterial::invariant_derivatives(double Ic,
                                                                          double J) const {
  return derivatives(terms(Ic, J));
}

GeneralModelCoefficients GeneralModelMaterial::coefficients(const Terms& t) {
  return {2.0 * t.dI, 4.0 * t.dII, t.dJJ, t.dJ};
}

Eigensystem GeneralModelMaterial::eigensystem_impl(const Mat3& F) const {
  return general_model_eigensystem(signed_svd(F),
                                   coefficients(terms(F.squaredNorm(), F.determinant())));
}

Evaluation GeneralModelMaterial::evaluate_impl(const Mat3& F, Projection mode) const {
  const Terms t = terms(F.squaredNorm(), F.determinant());
  Evaluation e;
  e.psi = t.psi;
  e.P = 2.0 * t.dI * F + t.dJ * cofactor(F);
  if (mode == Projection::None) {
    e.hessian = hessian_from(derivatives(t), F);  // Eq. 41 directly, no SVD
  } else {
    e.hessian = general_model_eigensystem(signed_svd(F), coefficients(t))
                    .projected(mode, projection_floor());
  }
  return e;
}

double ShiftedVolume::psi(double J) const {
  const double d = J - 1.0;
  return 0.5 * lambda * d * d - shift * d + shift * shift / (2.0 * lambda);
}

}  // namespace sinew
