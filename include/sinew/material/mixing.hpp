#pragma once
// Mixing and matching materials (paper 002 §6). A separable family's energy, once
// normalised, splits into a lambda- and a mu-part (Eq. 19):
//   psi = lambda_Lame psi_lambda + mu_Lame psi_mu,
// psi_lambda being the family normalised to (lambda_Lame, mu_Lame) = (1, 0) and psi_mu to
// (0, 1). A new material takes psi_lambda from one family and psi_mu from another, each with
// its own nonlinearity exponent (Eq. 20):
//   psi = lambda_Lame / a1^2 psi_lambda(s^a1) + mu_Lame / a2^2 psi_mu(s^a2).
// Its Lamé parameters are (lambda_Lame, mu_Lame) by construction.
#include <memory>

#include "sinew/material/catalog.hpp"
#include "sinew/material/lame.hpp"

namespace sinew {

class MixedMaterial final : public StretchMaterial {
 public:
  // lambda_part must have Lamé parameters (1, 0) and mu_part (0, 1) (checked to 1e-8;
  // sinew::Error otherwise); each is wrapped with its exponent (NonlinearMaterial) when != 1.
  MixedMaterial(std::shared_ptr<const Material> lambda_part,
                std::shared_ptr<const Material> mu_part, const Lame& lame,
                double alpha_lambda = 1.0, double alpha_mu = 1.0);

  std::string name() const override;
  Domain domain() const override;  // J > 0 only if either part needs it

  const Lame& lame() const { return lame_; }

  double psi_stretch(const Vec3& s) const override;
  Vec3 grad_stretch(const Vec3& s) const override;
  Mat3 hess_stretch(const Vec3& s) const override;
  // The pair quotients are linear in the stresses, so they are the weighted sums of the
  // parts' own (exact) pair eigenvalues.
  void pair_eigenvalues(const Vec3& s, const Vec3& p, const Mat3& h, Vec3& twist,
                        Vec3& flip) const override;

 protected:
  Eigensystem eigensystem_impl(const Mat3& F) const override;
  Evaluation evaluate_impl(const Mat3& F, Projection mode) const override;

 private:
  struct Parts;  // both parts' derivatives at one s, weighted and summed
  Parts at(const Vec3& s) const;

  std::shared_ptr<const Material> lambda_part_, mu_part_;
  Lame lame_;
};

// The family normalised to (1, 0), respectively (0, 1): the parts of Eq. 19. Only separable
// families qualify, and the lambda-part needs a family with a volume term (two normalized
// parameters). Other parameters and functions come from `base`.
MaterialParameters lambda_part_parameters(const MaterialInfo& family,
                                          const MaterialParameters& base = {});
MaterialParameters mu_part_parameters(const MaterialInfo& family,
                                      const MaterialParameters& base = {});

struct MixedParameters {
  MaterialParameters lambda_part;  // lambda family at (1, 0)
  MaterialParameters mu_part;      // mu family at (0, 1)
};

// Eq. 20 from two catalog families. `resolved`, if given, receives the parts' parameters.
std::shared_ptr<const MixedMaterial> make_mixed_material(
    const MaterialInfo& lambda_family, const MaterialParameters& lambda_base,
    const MaterialInfo& mu_family, const MaterialParameters& mu_base, const Lame& lame,
    double alpha_lambda = 1.0, double alpha_mu = 1.0, MixedParameters* resolved = nullptr);

}  // namespace sinew
