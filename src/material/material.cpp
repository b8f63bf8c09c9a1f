#include "sinew/material/material.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

Projection parse_projection(const std::string& text) {
  if (text == "clamp") return Projection::Clamp;
  if (text == "abs") return Projection::Abs;
  if (text == "none") return Projection::None;
  throw Error(fmt::format("unknown projection '{}' (expected clamp, abs or none)", text),
              "projection");
}

const char* to_string(Projection p) {
  switch (p) {
    case Projection::Clamp: return "clamp";
    case Projection::Abs: return "abs";
    case Projection::None: return "none";
  }
  return "?";
}

Mat9 Eigensystem::reconstruct() const {
  const Mat9 scaled = vectors * values.asDiagonal();
  return scaled.lazyProduct(vectors.transpose());
}

Mat9 Eigensystem::projected(Projection mode, double floor) const {
  Vec9 v = values;
  for (int k = 0; k < 9; ++k) {
    if (mode == Projection::Clamp) v(k) = std::max(v(k), floor);
    if (mode == Projection::Abs) v(k) = std::abs(v(k));
  }
  // Coefficient-based 9x9 product (Eigen would send vectors * diag * vectors^T through its
  // general blocked GEMM, whose set-up costs more than the product at this size).
  const Mat9 scaled = vectors * v.asDiagonal();
  return scaled.lazyProduct(vectors.transpose());
}

Eigen::SelfAdjointEigenSolver<Mat3> symmetric_eigen3(const Mat3& A) {
  // Closed form first (trigonometric cubic + cross products, ~100 ns). Its eigenvectors lose
  // accuracy when two eigenvalues nearly coincide; there the iterative solver (~300 ns) is
  // exact to rounding, so use it only then.
  Eigen::SelfAdjointEigenSolver<Mat3> es;
  es.computeDirect(A);
  const Vec3& v = es.eigenvalues();  // ascending
  const double scale = std::max(v.cwiseAbs().maxCoeff(), 1e-300);
  if (std::min(v(1) - v(0), v(2) - v(1)) < 1e-3 * scale) es.compute(A);
  return es;
}

// ---------------------------------------------------------------- public F view

bool Material::in_domain(const Mat3& F) const {
  if (!F.allFinite()) return false;
  if (domain() == Domain::PositiveJ) return F.determinant() > 0.0;
  return true;
}

void Material::check_domain(const Mat3& F) const {
  if (!F.allFinite()) throw Error("deformation gradient has a non-finite entry", name());
  if (domain() == Domain::PositiveJ && !(F.determinant() > 0.0)) {
    throw Error(fmt::format("energy is defined only for J = det F > 0, got J = {:.6g} "
                            "(inverted or degenerate element)",
                            F.determinant()),
                name());
  }
}

double Material::psi(const Mat3& F) const {
  check_domain(F);
  return psi_impl(F);
}
Mat3 Material::pk1(const Mat3& F) const {
  check_domain(F);
  return pk1_impl(F);
}
Mat9 Material::hessian(const Mat3& F) const {
  check_domain(F);
  return hessian_impl(F);
}
Eigensystem Material::eigensystem(const Mat3& F) const {
  check_domain(F);
  return eigensystem_impl(F);
}
Mat9 Material::projected_hessian(const Mat3& F, Projection mode) const {
  check_domain(F);
  if (mode == Projection::None) return hessian_impl(F);
  return eigensystem_impl(F).projected(mode, projection_floor());
}
Evaluation Material::evaluate(const Mat3& F, Projection mode) const {
  check_domain(F);
  return evaluate_impl(F, mode);
}

// ---------------------------------------------------------------- defaults via the SVD

double Material::psi_impl(const Mat3& F) const { return psi_stretch(signed_svd(F).sigma); }

Mat3 Material::pk1_impl(const Mat3& F) const {
  const SignedSvd s = signed_svd(F);
  return s.U * grad_stretch(s.sigma).asDiagonal() * s.V.transpose();  // paper 002 Eq. 1
}

Mat9 Material::hessian_impl(const Mat3& F) const { return eigensystem_impl(F).reconstruct(); }

Eigensystem Material::eigensystem_impl(const Mat3& F) const {
  const SignedSvd s = signed_svd(F);
  return stretch_eigensystem(s, grad_stretch(s.sigma), hess_stretch(s.sigma));
}

Evaluation Material::evaluate_impl(const Mat3& F, Projection mode) const {
  const SignedSvd s = signed_svd(F);
  const Vec3 p = grad_stretch(s.sigma);
  Evaluation e;
  e.psi = psi_stretch(s.sigma);
  e.P = s.U * p.asDiagonal() * s.V.transpose();
  const Eigensystem es = stretch_eigensystem(s, p, hess_stretch(s.sigma));
  e.hessian = mode == Projection::None ? es.reconstruct() : es.projected(mode, projection_floor());
  return e;
}

void Material::pair_eigenvalues(const Vec3& sigma, const Vec3& p, const Mat3& h, Vec3& twist,
                                Vec3& flip) const {
  // Below this relative gap the divided difference loses digits to cancellation faster
  // than the limit formula (error O(gap^2)) loses accuracy; eps^(1/3) balances the two.
  constexpr double kGap = 6e-6;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double scale = std::abs(sigma(i)) + std::abs(sigma(j)) + 1e-300;
    const double mean_diag = 0.5 * (h(i, i) + h(j, j));
    const double diff = sigma(i) - sigma(j), sum = sigma(i) + sigma(j);
    flip(k) = std::abs(diff) > kGap * scale ? (p(i) - p(j)) / diff : mean_diag - h(i, j);
    twist(k) = std::abs(sum) > kGap * scale ? (p(i) + p(j)) / sum : mean_diag + h(i, j);
  }
}

Mat9 isotropic_eigenvectors(const SignedSvd& s, const Mat3& Q) {
  Mat9 vectors;
  const double r = 1.0 / std::sqrt(2.0);
  for (int k = 0; k < 3; ++k) {
    vectors.col(k) = vec(s.U * Q.col(k).asDiagonal() * s.V.transpose());
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    Mat3 D = Mat3::Zero();
    D(i, j) = r;
    D(j, i) = -r;
    vectors.col(3 + k) = vec(s.U * D * s.V.transpose());  // twist (paper 000 Eq. 35)
    D(j, i) = r;
    vectors.col(6 + k) = vec(s.U * D * s.V.transpose());  // flip (paper 000 Eq. 37)
  }
  return vectors;
}

Eigensystem Material::stretch_eigensystem(const SignedSvd& s, const Vec3& p,
                                          const Mat3& h) const {
  const auto block = symmetric_eigen3(h);
  Vec3 twist, flip;
  pair_eigenvalues(s.sigma, p, h, twist, flip);
  Eigensystem es;
  es.values << block.eigenvalues(), twist, flip;
  es.vectors = isotropic_eigenvectors(s, block.eigenvectors());
  return es;
}

// ---------------------------------------------------------------- invariant materials

namespace {
Vec3 stretch_cofactor(const Vec3& s) { return {s(1) * s(2), s(0) * s(2), s(0) * s(1)}; }
}  // namespace

double InvariantMaterial::psi_stretch(const Vec3& s) const {
  return invariant_derivatives(s.squaredNorm(), s.prod()).psi;
}

Vec3 InvariantMaterial::grad_stretch(const Vec3& s) const {
  const Derivatives d = invariant_derivatives(s.squaredNorm(), s.prod());
  return 2.0 * d.dI * s + d.dJ * stretch_cofactor(s);
}

Mat3 InvariantMaterial::hess_stretch(const Vec3& s) const {
  return stretch_block(invariant_derivatives(s.squaredNorm(), s.prod()), s);
}

Mat3 InvariantMaterial::stretch_block(const Derivatives& d, const Vec3& s) {
  const Vec3 g = stretch_cofactor(s);
  Mat3 volume;  // d^2 J / d sigma^2
  volume << 0.0, s(2), s(1),
            s(2), 0.0, s(0),
            s(1), s(0), 0.0;
  return 2.0 * d.dI * Mat3::Identity() + 4.0 * d.dII * s * s.transpose() +
         2.0 * d.dIJ * (s * g.transpose() + g * s.transpose()) + d.dJJ * g * g.transpose() +
         d.dJ * volume;
}

void InvariantMaterial::pair_eigenvalues(const Vec3& s, const Vec3&, const Mat3&, Vec3& twist,
                                         Vec3& flip) const {
  pair_eigenvalues_from(invariant_derivatives(s.squaredNorm(), s.prod()), s, twist, flip);
}

void InvariantMaterial::pair_eigenvalues_from(const Derivatives& d, const Vec3& s, Vec3& twist,
                                              Vec3& flip) {
  for (int k = 0; k < 3; ++k) {
    twist(k) = 2.0 * d.dI + d.dJ * s(k);
    flip(k) = 2.0 * d.dI - d.dJ * s(k);
  }
}

Eigensystem InvariantMaterial::eigensystem_impl(const Mat3& F) const {
  const SignedSvd s = signed_svd(F);
  return invariant_eigensystem(invariant_derivatives(F.squaredNorm(), F.determinant()), s);
}

Eigensystem InvariantMaterial::invariant_eigensystem(const Derivatives& d, const SignedSvd& s) {
  const auto block = symmetric_eigen3(stretch_block(d, s.sigma));
  Vec3 twist, flip;
  pair_eigenvalues_from(d, s.sigma, twist, flip);
  Eigensystem es;
  es.values << block.eigenvalues(), twist, flip;
  es.vectors = isotropic_eigenvectors(s, block.eigenvectors());
  return es;
}

Evaluation InvariantMaterial::evaluate_impl(const Mat3& F, Projection mode) const {
  // One set of invariant derivatives serves Psi, P and the Hessian.
  const Derivatives d = invariant_derivatives(F.squaredNorm(), F.determinant());
  Evaluation e;
  e.psi = d.psi;
  e.P = 2.0 * d.dI * F + d.dJ * cofactor(F);
  e.hessian = mode == Projection::None
                  ? hessian_from(d, F)
                  : invariant_eigensystem(d, signed_svd(F)).projected(mode, projection_floor());
  return e;
}

double InvariantMaterial::psi_impl(const Mat3& F) const {
  return invariant_derivatives(F.squaredNorm(), F.determinant()).psi;
}

Mat3 InvariantMaterial::pk1_impl(const Mat3& F) const {
  const Derivatives d = curvature_derivatives(F.squaredNorm(), F.determinant());
  return 2.0 * d.dI * F + d.dJ * cofactor(F);
}

Mat9 InvariantMaterial::hessian_impl(const Mat3& F) const {
  return hessian_from(curvature_derivatives(F.squaredNorm(), F.determinant()), F);
}

Mat9 InvariantMaterial::hessian_from(const Derivatives& d, const Mat3& F) {
  const Vec9 f = vec(F);
  const Vec9 g = vec(cofactor(F));
  return 2.0 * d.dI * Mat9::Identity() + 4.0 * d.dII * f * f.transpose() +
         2.0 * d.dIJ * (f * g.transpose() + g * f.transpose()) + d.dJJ * g * g.transpose() +
         d.dJ * volume_hessian(F);
}

}  // namespace sinew
