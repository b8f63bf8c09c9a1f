// Registration of the material families of paper 002 Table 1 (see docs/_parts/table1.md for
// the formulas, the Lame parameters and the choices made where the extracted table is unclear).
#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/material/expression.hpp"
#include "sinew/material/families.hpp"

namespace sinew {

namespace {

// A user function of the family, parsed with the family's numeric parameters as constants.
ScalarFunction user_function(const MaterialParameters& p, const std::string& key) {
  try {
    return ScalarFunction::parse(p.functions.at(key), p.values);
  } catch (const Error& e) {
    throw e.within(fmt::format("function '{}'", key));
  }
}

double v(const MaterialParameters& p, const std::string& key) { return p.values.at(key); }

const ParameterSpec kLambda{"lambda", 1.0, "first Lame parameter"};
const ParameterSpec kMu{"mu", 1.0, "shear modulus (second Lame parameter)"};

}  // namespace

void register_isotropic_families(std::vector<MaterialInfo>& out) {
  out.push_back({"linear_corotational", "Linear corotational", "paper 002 Table 1; paper 000 Eq. 3",
                 "mu sum (s_i - 1)^2 + lambda/2 (s_0 + s_1 + s_2 - 3)^2",
                 {{"lambda", 1.0, "first Lame parameter"}, {"mu", 1.0, "shear modulus"}},
                 {},
                 {"lambda", "mu"},
                 true,
                 true,
                 [](const MaterialParameters& p) {
                   return std::make_unique<LinearCorotational>(p.values.at("lambda"),
                                                               p.values.at("mu"));
                 }});

  out.push_back({"hencky", "Hencky (Seth-Hill m = 0)", "paper 002 Table 1",
                 "mu sum log^2 s_i + lambda/2 log^2 J",
                 {kLambda, kMu},
                 {},
                 {"lambda", "mu"},
                 true,
                 true,
                 [](const MaterialParameters& p) {
                   return std::make_unique<Hencky>(v(p, "lambda"), v(p, "mu"));
                 }});

  out.push_back({"seth_hill", "Seth-Hill family", "paper 002 Table 1 (Seth 1964)",
                 "mu/m^2 sum (s_i^m - 1)^2 + lambda/(2 m^2) (sum s_i^m - 3)^2, m != 0",
                 {kLambda, kMu, {"m", 3.0, "Seth-Hill exponent (Table 1 alpha); 1 = corotational, 2 = StVK"}},
                 {},
                 {"lambda", "mu"},
                 true,
                 true,
                 [](const MaterialParameters& p) {
                   return std::make_unique<SethHill>(v(p, "lambda"), v(p, "mu"), v(p, "m"));
                 }});

  out.push_back({"symmetric_seth_hill", "Symmetric Seth-Hill", "paper 002 Table 1 (Bazant 1998)",
                 "mu/(4 m^2) sum (s_i^m - s_i^-m)^2 + lambda/(8 m^2) (sum (s_i^m - s_i^-m))^2, m != 0",
                 {kLambda, kMu, {"m", 1.0, "exponent (Table 1 alpha)"}},
                 {},
                 {"lambda", "mu"},
                 true,
                 true,
                 [](const MaterialParameters& p) {
                   return std::make_unique<SymmetricSethHill>(v(p, "lambda"), v(p, "mu"), v(p, "m"));
                 }});

  out.push_back({"hill", "Hill family", "paper 002 Table 1 (Hill 1968)",
                 "mu sum f(s_i)^2 + lambda/2 (sum f(s_i))^2, f(1) = 0, f'(1) = 1",
                 {kLambda, kMu},
                 {{"f", "log(x)", "strain measure f(x) with f(1) = 0, f'(1) = 1"}},
                 {"lambda", "mu"},
                 true,
                 true,
                 [](const MaterialParameters& p) {
                   return std::make_unique<Hill>(v(p, "lambda"), v(p, "mu"), user_function(p, "f"));
                 }});

  out.push_back({"neo_hookean", "Neo-Hookean (standard)", "paper 002 Table 1",
                 "mu/2 (I_C - 3) - mu log J + lambda/2 log^2 J",
                 {kLambda, kMu},
                 {},
                 {"lambda", "mu"},
                 true,
                 true,
                 [](const MaterialParameters& p) {
                   return std::make_unique<NeoHookean>(v(p, "lambda"), v(p, "mu"));
                 }});

  out.push_back({"neo_hookean_ogden", "Neo-Hookean (Ogden)", "paper 002 Table 1",
                 "mu/2 (I_C - 3) - mu log J + lambda/2 (J - 1)^2",
                 {kLambda, kMu},
                 {},
                 {"lambda", "mu"},
                 true,
                 true,
                 [](const MaterialParameters& p) {
                   return std::make_unique<NeoHookeanOgden>(v(p, "lambda"), v(p, "mu"));
                 }});

  out.push_back({"sts", "STS material", "paper 002 Table 1 (Pai et al. 2018)",
                 "mu/2 (sum s_i^2 - 3) - mu log J + lambda/2 log^2 J + mu4/8 sum (s_i^2 - 1)^4",
                 {kLambda, kMu, {"mu4", 0.2, "coefficient of the quartic Green-strain term"}},
                 {},
                 {"lambda", "mu"},
                 false,  // the mu4 term scales with neither Lame parameter
                 true,
                 [](const MaterialParameters& p) {
                   return std::make_unique<Sts>(v(p, "lambda"), v(p, "mu"), v(p, "mu4"));
                 }});

  out.push_back({"valanis_landel", "Valanis-Landel (original)",
                 "paper 002 Table 1 (Valanis and Landel 1967)",
                 "2 mu sum (s_i (log s_i - 1) + 1) + lambda/2 log^2 J",
                 {kLambda, kMu},
                 {},
                 {"lambda", "mu"},
                 true,
                 true,
                 [](const MaterialParameters& p) {
                   return std::make_unique<ValanisLandel>(v(p, "lambda"), v(p, "mu"));
                 }});

  out.push_back({"valanis_landel_new", "Valanis-Landel (new)",
                 "paper 002 Table 1 (Valanis 2022; Chen et al. 2023)",
                 "sum f(s_i) + h(J), f'(1) + h'(1) = 0",
                 {kLambda, kMu},
                 {{"f", "mu*(x-1)^2", "per-stretch term f(x); mu_Lame = f''(1)/2 when h'(1) = 0"},
                  {"h", "lambda/2*log(x)^2", "volume term h(J); lambda_Lame = h''(1) when h'(1) = 0"}},
                 {"lambda", "mu"},
                 true,
                 true,
                 [](const MaterialParameters& p) {
                   return std::make_unique<ValanisLandelNew>(user_function(p, "f"),
                                                             user_function(p, "h"));
                 }});

  out.push_back({"valanis_landel_xu", "Valanis-Landel (Xu's version)",
                 "paper 002 Table 1 (Xu et al. 2015)",
                 "sum f(s_i) + sum_{i<j} g(s_i s_j) + h(J), f'(1) + 2 g'(1) + h'(1) = 0",
                 {kLambda, kMu},
                 {{"f", "mu/2*(x-1)^2", "per-stretch term f(x)"},
                  {"g", "mu/2*(x-1)^2", "pair term g(s_i s_j), summed over i < j"},
                  {"h", "(lambda-mu)/2*log(x)^2", "volume term h(J)"}},
                 {"lambda", "mu"},
                 false,
                 true,
                 [](const MaterialParameters& p) {
                   return std::make_unique<ValanisLandelXu>(
                       user_function(p, "f"), user_function(p, "g"), user_function(p, "h"));
                 }});

  out.push_back({"peng_landel", "Peng-Landel", "paper 002 Table 1 (Peng and Landel 1972)",
                 "E sum (s_i - 1 - L_i - L_i^2/6 + L_i^3/18 - L_i^4/216), L_i = log s_i",
                 {{"E", 3.0, "modulus (mu_Lame = E/3, lambda_Lame = 0)"}},
                 {},
                 {"E"},
                 true,  // linear in its one parameter: usable as a mu-part (paper 002 §6)
                 true,
                 [](const MaterialParameters& p) { return std::make_unique<PengLandel>(v(p, "E")); }});

  out.push_back({"arap", "As-rigid-as-possible", "paper 002 Table 1 (Sorkine and Alexa 2007)",
                 "mu ||F - R||^2 = mu sum (s_i - 1)^2",
                 {{"mu", 1.0, "scale (1 = the table's energy); mu_Lame = mu"}},
                 {},
                 {"mu"},
                 true,  // linear in its one parameter: usable as a mu-part (paper 002 §6)
                 true,
                 [](const MaterialParameters& p) { return std::make_unique<Arap>(v(p, "mu")); }});

  out.push_back({"symmetric_arap", "Symmetric ARAP", "paper 002 Table 1 (Shtengel et al. 2017)",
                 "mu/2 (||F - R||^2 + ||F^-1 - R^-1||^2) = mu/2 sum ((s_i - 1)^2 + (1 - 1/s_i)^2)",
                 {{"mu", 1.0, "shear modulus (mu_Lame = mu)"}},
                 {},
                 {"mu"},
                 true,  // linear in its one parameter: usable as a mu-part (paper 002 §6)
                 true,
                 [](const MaterialParameters& p) { return std::make_unique<SymmetricArap>(v(p, "mu")); }});

  out.push_back({"symmetric_dirichlet", "Symmetric Dirichlet",
                 "paper 002 Table 1 (Smith and Schaefer 2015)",
                 "mu/2 sum (s_i - 1/s_i)^2 = mu/2 (||F||^2 + ||F^-1||^2) - 3 mu",
                 {{"mu", 1.0, "scale (1 = the table's energy); mu_Lame = 2 mu"}},
                 {},
                 {"mu"},
                 true,  // linear in its one parameter: usable as a mu-part (paper 002 §6)
                 true,
                 [](const MaterialParameters& p) {
                   return std::make_unique<SymmetricDirichlet>(v(p, "mu"));
                 }});

  out.push_back({"ogden", "Ogden (three terms)", "paper 002 Table 1 (Ogden 1972)",
                 "sum_p mu_p/alpha_p (sum_i s_i^alpha_p - 3), p = 1..3; terms with mu_p = 0 inactive",
                 {{"mu1", 0.35, "coefficient of term 1"},
                  {"alpha1", 3.0, "exponent of term 1"},
                  {"mu2", 0.1, "coefficient of term 2"},
                  {"alpha2", 5.0, "exponent of term 2"},
                  {"mu3", -0.45, "coefficient of term 3"},
                  {"alpha3", -1.0, "exponent of term 3"}},
                 {},
                 {"mu1"},
                 false,
                 false,  // P(I) = (mu1 + mu2 + mu3) I; the defaults sum to 0
                 [](const MaterialParameters& p) {
                   return std::make_unique<Ogden>(
                       std::vector<double>{v(p, "mu1"), v(p, "mu2"), v(p, "mu3")},
                       std::vector<double>{v(p, "alpha1"), v(p, "alpha2"), v(p, "alpha3")});
                 }});

  out.push_back({"mooney_rivlin", "Mooney-Rivlin (as in Table 1)", "paper 002 Table 1",
                 "C1 J^(-2/3) (I_1 - 3) + C2 J^(-4/3) (I_2 - 3)",
                 {{"C1", 1.0, "first coefficient (mu_Lame = C1)"},
                  {"C2", -0.5, "second coefficient (lambda_Lame = -4/3 (2 C1 + 5 C2))"}},
                 {},
                 {"C1", "C2"},
                 false,
                 false,  // P(I) = (2 C1 + 4 C2) I; zero for the defaults (C2 = -C1/2)
                 [](const MaterialParameters& p) {
                   return std::make_unique<MooneyRivlin>(v(p, "C1"), v(p, "C2"));
                 }});
}

}  // namespace sinew
