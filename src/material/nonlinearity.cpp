#include "sinew/material/nonlinearity.hpp"

#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

double power_divided_difference(double x, double y, double beta) {
  if (x == y) return beta * std::pow(x, beta - 1.0);
  // x^b - y^b = y^b expm1(b r) and x - y = y expm1(r) with r = log(x / y); log1p of the
  // (exactly computed, for close x and y) relative gap keeps r accurate as x -> y.
  const double r = std::log1p((x - y) / y);
  return std::pow(y, beta - 1.0) * std::expm1(beta * r) / std::expm1(r);
}

struct NonlinearMaterial::Stretch {
  Vec3 s;  // the wrapper's stretches
  Vec3 t;  // s^alpha, where the base is evaluated
  Vec3 a;  // s^(alpha - 1) = dt/ds / alpha
  Vec3 P;  // base gradient at t
  Mat3 H;  // base Hessian at t
  Vec3 g;  // Eq. 17
  Mat3 h;  // Eq. 18
};

NonlinearMaterial::NonlinearMaterial(std::shared_ptr<const Material> base, double alpha)
    : base_(std::move(base)), alpha_(alpha) {
  if (!base_) throw Error("no base material", "nonlinearity");
  if (!std::isfinite(alpha_) || !(alpha_ > 0.0)) {
    throw Error(fmt::format("must be a positive finite number, got {}", alpha_),
                fmt::format("material '{}': alpha", base_->name()));
  }
}

std::string NonlinearMaterial::name() const {
  return fmt::format("{}[alpha={:g}]", base_->name(), alpha_);
}

Domain NonlinearMaterial::domain() const {
  // s^alpha is real only for s > 0; alpha = 1 is the base itself.
  return alpha_ == 1.0 ? base_->domain() : Domain::PositiveJ;
}

double NonlinearMaterial::psi_stretch(const Vec3& s) const {
  if (alpha_ == 1.0) return base_->psi_stretch(s);
  const Vec3 t = s.array().pow(alpha_);
  return base_->psi_stretch(t) / (alpha_ * alpha_);  // Eq. 16
}

Vec3 NonlinearMaterial::grad_stretch(const Vec3& s) const {
  if (alpha_ == 1.0) return base_->grad_stretch(s);
  const Vec3 t = s.array().pow(alpha_);
  const Vec3 a = s.array().pow(alpha_ - 1.0);
  return a.cwiseProduct(base_->grad_stretch(t)) / alpha_;  // Eq. 17
}

Mat3 NonlinearMaterial::hess_stretch(const Vec3& s) const { return at(s).h; }

NonlinearMaterial::Stretch NonlinearMaterial::at(const Vec3& s) const {
  Stretch st;
  st.s = s;
  if (alpha_ == 1.0) {
    st.t = s;
    st.a = Vec3::Ones();
  } else {
    st.t = s.array().pow(alpha_);
    st.a = s.array().pow(alpha_ - 1.0);
  }
  st.P = base_->grad_stretch(st.t);
  st.H = base_->hess_stretch(st.t);
  st.g = st.a.cwiseProduct(st.P) / alpha_;
  // Eq. 18: (alpha - 1)/alpha diag(s^(alpha-2) p) + diag(s^(alpha-1)) H diag(s^(alpha-1)).
  st.h = st.a.asDiagonal() * st.H * st.a.asDiagonal();
  if (alpha_ != 1.0) {
    for (int i = 0; i < 3; ++i) st.h(i, i) += (alpha_ - 1.0) / alpha_ * st.a(i) / s(i) * st.P(i);
  }
  return st;
}

void NonlinearMaterial::pairs(const Stretch& st, Vec3& twist, Vec3& flip) const {
  Vec3 base_twist, base_flip;
  base_->pair_eigenvalues(st.t, st.P, st.H, base_twist, base_flip);
  if (alpha_ == 1.0) {
    twist = base_twist;
    flip = base_flip;
    return;
  }
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    // a_i P_i - a_j P_j = (a_i + a_j)/2 (P_i - P_j) + (a_i - a_j)/2 (P_i + P_j), with
    // P_i - P_j = base_flip (t_i - t_j): every difference quotient stays finite as s_i -> s_j.
    const double dt = power_divided_difference(st.s(i), st.s(j), alpha_);        // dt/ds
    const double da = power_divided_difference(st.s(i), st.s(j), alpha_ - 1.0);  // da/ds
    flip(k) =
        (0.5 * (st.a(i) + st.a(j)) * base_flip(k) * dt + 0.5 * (st.P(i) + st.P(j)) * da) / alpha_;
    // s_i + s_j > 0 on the domain, so the twist quotient is safe as it stands.
    twist(k) = (st.g(i) + st.g(j)) / (st.s(i) + st.s(j));
  }
}

void NonlinearMaterial::pair_eigenvalues(const Vec3& s, const Vec3&, const Mat3&, Vec3& twist,
                                         Vec3& flip) const {
  pairs(at(s), twist, flip);
}

Eigensystem NonlinearMaterial::eigensystem_from(const SignedSvd& svd, const Stretch& st) const {
  const auto block = symmetric_eigen3(st.h);
  Vec3 twist, flip;
  pairs(st, twist, flip);
  Eigensystem es;
  es.values << block.eigenvalues(), twist, flip;
  es.vectors = isotropic_eigenvectors(svd, block.eigenvectors());
  return es;
}

double NonlinearMaterial::psi_impl(const Mat3& F) const {
  return alpha_ == 1.0 ? base_->psi(F) : Material::psi_impl(F);
}

Mat3 NonlinearMaterial::pk1_impl(const Mat3& F) const {
  return alpha_ == 1.0 ? base_->pk1(F) : Material::pk1_impl(F);
}

Mat9 NonlinearMaterial::hessian_impl(const Mat3& F) const {
  return alpha_ == 1.0 ? base_->hessian(F) : Material::hessian_impl(F);
}

Eigensystem NonlinearMaterial::eigensystem_impl(const Mat3& F) const {
  if (alpha_ == 1.0) return base_->eigensystem(F);
  const SignedSvd svd = signed_svd(F);
  return eigensystem_from(svd, at(svd.sigma));
}

Evaluation NonlinearMaterial::evaluate_impl(const Mat3& F, Projection mode) const {
  if (alpha_ == 1.0) return base_->evaluate(F, mode);
  const SignedSvd svd = signed_svd(F);
  const Stretch st = at(svd.sigma);
  Evaluation e;
  e.psi = base_->psi_stretch(st.t) / (alpha_ * alpha_);
  e.P = svd.U * st.g.asDiagonal() * svd.V.transpose();
  const Eigensystem es = eigensystem_from(svd, st);
  e.hessian = mode == Projection::None ? es.reconstruct() : es.projected(mode, projection_floor());
  return e;
}

}  // namespace sinew
