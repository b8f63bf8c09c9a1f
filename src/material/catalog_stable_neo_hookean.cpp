// Paper 000's families: the stable Neo-Hookean energies, the §5.3 extensions and the §5-6
// comparison models.
#include "sinew/material/catalog.hpp"
#include "sinew/material/families/corotational.hpp"
#include "sinew/material/families.hpp"

namespace sinew {

void register_stable_neo_hookean_families(std::vector<MaterialInfo>& out) {
  auto v = [](const MaterialParameters& p, const char* key) { return p.values.at(key); };

  out.push_back({"stable_neo_hookean", "Stable Neo-Hookean", "paper 000 Eq. 14",
                 "mu/2 (I_C - 3) + lambda/2 (J - alpha)^2 - mu/2 log(I_C + 1), "
                 "alpha = 1 + 3 mu / (4 lambda)",
                 {{"lambda", 10.0, "volume stiffness (SNH's own; lambda_Lame = lambda - 5/8 mu)"},
                  {"mu", 1.0, "shear stiffness (SNH's own; mu_Lame = 3/4 mu)"}},
                 {},
                 {"lambda", "mu"},
                 false,  // alpha depends on mu/lambda
                 true,
                 [v](const MaterialParameters& p) {
                   return std::make_unique<StableNeoHookean>(v(p, "lambda"), v(p, "mu"));
                 }});

  out.push_back({"stable_neo_hookean_eq13", "Stable Neo-Hookean without origin barrier",
                 "paper 000 Eq. 13, Appendix D",
                 "mu/2 (I_C - 3) - mu (J - 1) + lambda/2 (J - 1)^2",
                 {{"lambda", 10.0, "volume stiffness (lambda_Lame = lambda - mu)"},
                  {"mu", 1.0, "shear modulus (mu_Lame = mu)"}},
                 {},
                 {"lambda", "mu"},
                 true,
                 true,
                 [v](const MaterialParameters& p) {
                   return std::make_unique<StableNeoHookeanEq13>(v(p, "lambda"), v(p, "mu"));
                 }});

  out.push_back({"corotational", "Co-rotational", "paper 000 Eq. 3",
                 "mu ||F - R||_F^2 + lambda/2 tr^2(S - I)",
                 {{"lambda", 10.0, "first Lame parameter"}, {"mu", 1.0, "shear modulus"}},
                 {},
                 {"lambda", "mu"},
                 true,
                 true,
                 [v](const MaterialParameters& p) {
                   return std::make_unique<LinearCorotational>(v(p, "lambda"), v(p, "mu"),
                                                               "corotational");
                 }});

  out.push_back({"fixed_corotational", "Fixed co-rotational (Stomakhin et al. 2012)",
                 "paper 000 Eq. 49", "mu ||F - R||_F^2 + lambda/2 (J - 1)^2",
                 {{"lambda", 10.0, "first Lame parameter"}, {"mu", 1.0, "shear modulus"}},
                 {},
                 {"lambda", "mu"},
                 true,
                 true,
                 [v](const MaterialParameters& p) {
                   return std::make_unique<FixedCorotational>(v(p, "lambda"), v(p, "mu"));
                 }});

  out.push_back({"stvk", "St. Venant-Kirchhoff", "paper 000 Eq. 50",
                 "mu ||E||_F^2 + lambda/2 tr^2(E), E = (F^T F - I)/2",
                 {{"lambda", 10.0, "first Lame parameter"}, {"mu", 1.0, "shear modulus"}},
                 {},
                 {"lambda", "mu"},
                 true,
                 true,
                 [v](const MaterialParameters& p) {
                   return std::make_unique<StVK>(v(p, "lambda"), v(p, "mu"));
                 }});

  out.push_back({"stvk_kikuuwe", "StVK with Kikuuwe compression resistance",
                 "paper 000 Eq. 51; Kikuuwe et al. 2009",
                 "mu ||E||_F^2 + lambda/2 tr^2(E) + kappa/12 ((1 - J)/6)^3 [J < 1 only]",
                 {{"lambda", 10.0, "first Lame parameter"},
                  {"mu", 1.0, "shear modulus"},
                  {"kappa", 10.0, "compression resistance (the term is kappa (1 - J)^3 / 2592)"}},
                 {},
                 {"lambda", "mu"},
                 false,  // the kappa term belongs to neither the lambda- nor the mu-part
                 true,
                 [v](const MaterialParameters& p) {
                   return std::make_unique<StVKKikuuwe>(v(p, "lambda"), v(p, "mu"), v(p, "kappa"));
                 }});

  out.push_back({"fung", "Stabilised Fung", "paper 000 Eq. 53-56",
                 "mu0/2 (I_C - 3) + lambda/2 (J - alpha)^2 + gamma (exp(mu1/2 (I_C - 3)) - 1), "
                 "alpha = 1 + (mu0 + gamma mu1)/lambda",
                 {{"mu0", 1.0, "Neo-Hookean stiffness (mu_Lame = mu0 + gamma mu1)"},
                  {"mu1", 0.1, "exponential hardening rate"},
                  {"gamma", 1.0, "exponential hardening scale"},
                  {"lambda", 10.0, "volume stiffness"}},
                 {},
                 {"lambda", "mu0"},
                 false,
                 true,
                 [v](const MaterialParameters& p) {
                   return std::make_unique<Fung>(v(p, "mu0"), v(p, "mu1"), v(p, "gamma"),
                                                 v(p, "lambda"));
                 }});

  out.push_back({"arruda_boyce", "Stabilised Arruda-Boyce (three terms)", "paper 000 Eq. 58-61",
                 "mu/2 (I_C - 3) + mu beta1/4 (I_C^2 - 9) + mu beta2/6 (I_C^3 - 27) + "
                 "lambda/2 (J - alpha)^2, alpha = 1 + mu/lambda (1 + 3 beta1 + 9 beta2)",
                 {{"lambda", 10.0, "volume stiffness"},
                  {"mu", 1.0, "Neo-Hookean stiffness (mu_Lame = mu (1 + 3 beta1 + 9 beta2))"},
                  {"beta1", 0.1, "I_C^2 hardening coefficient"},
                  {"beta2", 0.01, "I_C^3 hardening coefficient"}},
                 {},
                 {"lambda", "mu"},
                 false,
                 true,
                 [v](const MaterialParameters& p) {
                   return std::make_unique<ArrudaBoyce>(v(p, "lambda"), v(p, "mu"), v(p, "beta1"),
                                                        v(p, "beta2"));
                 }});

  out.push_back({"neo_hookean_filtered", "Filtered Neo-Hookean (Irving 2004 / Teran 2005)",
                 "paper 000 Eq. 5, §6",
                 "mu/2 (I_C - 3) - mu L + lambda/2 L^2, L = sum l(sigma_i), l = log above "
                 "threshold, its 2nd-order Taylor expansion below",
                 {{"lambda", 10.0, "first Lame parameter"},
                  {"mu", 1.0, "shear modulus"},
                  {"threshold", 0.25, "filtering threshold sigma_f on the singular values"},
                  {"hessian_threshold", -1e-4, "eigenvalue floor epsilon_p of the clamp projection"}},
                 {},
                 {"lambda", "mu"},
                 true,
                 true,
                 [v](const MaterialParameters& p) {
                   return std::make_unique<NeoHookeanFiltered>(v(p, "lambda"), v(p, "mu"),
                                                               v(p, "threshold"),
                                                               v(p, "hessian_threshold"));
                 }});
}

}  // namespace sinew
