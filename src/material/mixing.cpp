#include "sinew/material/mixing.hpp"

#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/material/nonlinearity.hpp"
#include "sinew/material/normalization.hpp"

namespace sinew {

namespace {

std::shared_ptr<const Material> with_alpha(std::shared_ptr<const Material> part, double alpha,
                                           const char* which) {
  if (!part) throw Error("missing part", fmt::format("mix: {}-part", which));
  if (!std::isfinite(alpha) || !(alpha > 0.0)) {
    throw Error(fmt::format("must be a positive finite number, got {}", alpha),
                fmt::format("mix: alpha_{}", which));
  }
  if (alpha == 1.0) return part;
  return std::make_shared<NonlinearMaterial>(std::move(part), alpha);
}

void check_unit_lame(const Material& part, const Lame& expected, const char* which) {
  const Lame l = lame_from_energy(part);
  if (!(std::abs(l.lambda - expected.lambda) <= 1e-8 && std::abs(l.mu - expected.mu) <= 1e-8)) {
    throw Error(fmt::format("the {}-part must have (lambda_Lame, mu_Lame) = ({:g}, {:g}), got "
                            "({:.6g}, {:.6g})",
                            which, expected.lambda, expected.mu, l.lambda, l.mu),
                fmt::format("mix: {}-part '{}'", which, part.name()));
  }
}

void require_separable(const MaterialInfo& family, const char* which) {
  if (family.separable) return;
  std::string names;
  for (const auto& f : MaterialCatalog::instance().all()) {
    if (f.separable) names += (names.empty() ? "" : ", ") + f.name;
  }
  throw Error(fmt::format("family is not separable into lambda- and mu-parts (paper 002 Eq. 19), "
                          "so it cannot be mixed (separable families: {})",
                          names.empty() ? "none" : names),
              fmt::format("mix: {}-part: material '{}'", which, family.name));
}

}  // namespace

MaterialParameters lambda_part_parameters(const MaterialInfo& family,
                                          const MaterialParameters& base) {
  require_separable(family, "lambda");
  if (family.normalized.size() != 2) {
    throw Error(
        "family has no volume term to take a lambda-part from (lambda_Lame is fixed "
        "by its parameters or identically 0)",
        fmt::format("mix: lambda-part: material '{}'", family.name));
  }
  return normalize(family, base, Lame{1.0, 0.0});
}

MaterialParameters mu_part_parameters(const MaterialInfo& family, const MaterialParameters& base) {
  require_separable(family, "mu");
  return normalize(family, base, Lame{0.0, 1.0});
}

struct MixedMaterial::Parts {
  Vec3 g = Vec3::Zero();  // weighted gradient sum
  Mat3 h = Mat3::Zero();  // weighted Hessian sum
  Vec3 twist = Vec3::Zero(), flip = Vec3::Zero();
};

MixedMaterial::MixedMaterial(std::shared_ptr<const Material> lambda_part,
                             std::shared_ptr<const Material> mu_part, const Lame& lame,
                             double alpha_lambda, double alpha_mu)
    : lame_(lame) {
  if (!std::isfinite(lame.lambda) || !std::isfinite(lame.mu)) {
    throw Error("Lame parameters must be finite", "mix");
  }
  if (lambda_part) check_unit_lame(*lambda_part, {1.0, 0.0}, "lambda");
  if (mu_part) check_unit_lame(*mu_part, {0.0, 1.0}, "mu");
  lambda_part_ = with_alpha(std::move(lambda_part), alpha_lambda, "lambda");
  mu_part_ = with_alpha(std::move(mu_part), alpha_mu, "mu");
}

std::string MixedMaterial::name() const {
  return fmt::format("mix[lambda={}, mu={}]", lambda_part_->name(), mu_part_->name());
}

Domain MixedMaterial::domain() const {
  return lambda_part_->domain() == Domain::PositiveJ || mu_part_->domain() == Domain::PositiveJ
             ? Domain::PositiveJ
             : Domain::All;
}

double MixedMaterial::psi_stretch(const Vec3& s) const {
  return lame_.lambda * lambda_part_->psi_stretch(s) + lame_.mu * mu_part_->psi_stretch(s);
}

Vec3 MixedMaterial::grad_stretch(const Vec3& s) const {
  return lame_.lambda * lambda_part_->grad_stretch(s) + lame_.mu * mu_part_->grad_stretch(s);
}

Mat3 MixedMaterial::hess_stretch(const Vec3& s) const {
  return lame_.lambda * lambda_part_->hess_stretch(s) + lame_.mu * mu_part_->hess_stretch(s);
}

MixedMaterial::Parts MixedMaterial::at(const Vec3& s) const {
  Parts out;
  for (const auto& [weight, part] :
       {std::pair{lame_.lambda, lambda_part_.get()}, std::pair{lame_.mu, mu_part_.get()}}) {
    const Vec3 p = part->grad_stretch(s);
    const Mat3 h = part->hess_stretch(s);
    Vec3 twist, flip;
    part->pair_eigenvalues(s, p, h, twist, flip);
    out.g += weight * p;
    out.h += weight * h;
    out.twist += weight * twist;
    out.flip += weight * flip;
  }
  return out;
}

void MixedMaterial::pair_eigenvalues(const Vec3& s, const Vec3&, const Mat3&, Vec3& twist,
                                     Vec3& flip) const {
  const Parts parts = at(s);
  twist = parts.twist;
  flip = parts.flip;
}

Eigensystem MixedMaterial::eigensystem_impl(const Mat3& F) const {
  const SignedSvd svd = signed_svd(F);
  const Parts parts = at(svd.sigma);
  const auto block = symmetric_eigen3(parts.h);
  Eigensystem es;
  es.values << block.eigenvalues(), parts.twist, parts.flip;
  es.vectors = isotropic_eigenvectors(svd, block.eigenvectors());
  return es;
}

Evaluation MixedMaterial::evaluate_impl(const Mat3& F, Projection mode) const {
  const SignedSvd svd = signed_svd(F);
  const Parts parts = at(svd.sigma);
  Evaluation e;
  e.psi = psi_stretch(svd.sigma);
  e.P = svd.U * parts.g.asDiagonal() * svd.V.transpose();
  const auto block = symmetric_eigen3(parts.h);
  Eigensystem es;
  es.values << block.eigenvalues(), parts.twist, parts.flip;
  es.vectors = isotropic_eigenvectors(svd, block.eigenvectors());
  e.hessian = mode == Projection::None ? es.reconstruct() : es.projected(mode, projection_floor());
  return e;
}

std::shared_ptr<const MixedMaterial> make_mixed_material(
    const MaterialInfo& lambda_family, const MaterialParameters& lambda_base,
    const MaterialInfo& mu_family, const MaterialParameters& mu_base, const Lame& lame,
    double alpha_lambda, double alpha_mu, MixedParameters* resolved) {
  MixedParameters parts{lambda_part_parameters(lambda_family, lambda_base),
                        mu_part_parameters(mu_family, mu_base)};
  std::shared_ptr<const Material> lambda_part, mu_part;
  try {
    lambda_part = lambda_family.make(parts.lambda_part);
  } catch (const Error& e) {
    throw e.within(fmt::format("mix: lambda-part: material '{}'", lambda_family.name));
  }
  try {
    mu_part = mu_family.make(parts.mu_part);
  } catch (const Error& e) {
    throw e.within(fmt::format("mix: mu-part: material '{}'", mu_family.name));
  }
  auto mixed = std::make_shared<const MixedMaterial>(std::move(lambda_part), std::move(mu_part),
                                                     lame, alpha_lambda, alpha_mu);
  if (resolved) *resolved = std::move(parts);
  return mixed;
}

}  // namespace sinew
