// Family-specific checks of the paper 002 Table 1 materials: identities between families,
// non-default parameters and user functions under the finite-difference oracles, the
// readings chosen where the extracted table is unclear, and every rejection path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "material_test_support.hpp"
#include "sinew/core/error.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/material/lame.hpp"
#include "sinew/material/families.hpp"
#include "sinew/material/divided_difference.hpp"

namespace sinew {
namespace {

using test::rel_error;

std::unique_ptr<Material> make(const std::string& name, std::map<std::string, double> values = {},
                               std::map<std::string, std::string> functions = {}) {
  MaterialParameters p;
  p.values = std::move(values);
  p.functions = std::move(functions);
  return MaterialCatalog::instance().make(name, p);
}

std::vector<test::SampleF> samples(const Material& m, unsigned seed = 77u) {
  return test::sample_set(seed, 6, m.domain() == Domain::All);
}

// P and the Hessian against Richardson central differences, and the analytic eigenvalues
// against a numeric 9x9 eigensolve. P is compared with a floor in stress units (1e-5 of the
// Hessian norm, the stress of a unit strain) because at rest P = 0 and the differences only
// resolve it to O(h^4 d^5 psi).
void expect_derivatives_match(const Material& m, const std::vector<test::SampleF>& set,
                              const std::string& label) {
  for (const auto& s : set) {
    const Mat9 H = m.hessian(s.F);
    const double scale = std::max(1.0, H.norm());
    EXPECT_LE(rel_error(m.pk1(s.F), test::fd_pk1(m, s.F), 1e-5 * scale), 1e-6)
        << label << " " << test::describe(s);
    EXPECT_LE(rel_error(H, test::fd_hessian(m, s.F)), 1e-6) << label << " " << test::describe(s);
    Vec9 analytic = m.eigensystem(s.F).values;
    std::sort(analytic.data(), analytic.data() + 9);
    EXPECT_LE((analytic - test::numeric_eigenvalues(H)).norm() / scale, 1e-8)
        << label << " " << test::describe(s);
  }
}

// Two materials agree on psi, P and the Hessian (P relative to the stress of a unit strain
// at least, since at rest both are rounding noise around 0).
void expect_same_material(const Material& a, const Material& b,
                          const std::vector<test::SampleF>& set, const std::string& label) {
  for (const auto& s : set) {
    EXPECT_NEAR(a.psi(s.F), b.psi(s.F), 1e-11 * std::max(1.0, std::abs(b.psi(s.F))))
        << label << " " << test::describe(s);
    const double stress = std::max(1.0, b.hessian(s.F).norm());
    EXPECT_LE(rel_error(a.pk1(s.F), b.pk1(s.F), stress), 1e-10) << label << " " << test::describe(s);
    EXPECT_LE(rel_error(a.hessian(s.F), b.hessian(s.F)), 1e-10) << label << " " << test::describe(s);
  }
}

void expect_error_containing(const std::function<void()>& fn,
                             std::initializer_list<std::string> fragments) {
  try {
    fn();
    ADD_FAILURE() << "no sinew::Error thrown";
  } catch (const Error& e) {
    for (const auto& f : fragments) {
      EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
    }
  }
}

// ------------------------------------------------------------------- Seth-Hill family

TEST(SethHill, ExponentOneIsLinearCorotational) {
  const auto sh = make("seth_hill", {{"lambda", 3.7}, {"mu", 1.3}, {"m", 1.0}});
  const auto cr = make("linear_corotational", {{"lambda", 3.7}, {"mu", 1.3}});
  EXPECT_EQ(sh->domain(), Domain::All);
  expect_same_material(*sh, *cr, samples(*sh), "seth_hill m=1 vs linear_corotational");
}

// StVK written independently: E = (F^T F - I)/2, Psi = mu ||E||^2 + lambda/2 tr(E)^2,
// P = F (2 mu E + lambda tr(E) I).
TEST(SethHill, ExponentTwoIsStVK) {
  const double lambda = 2.5, mu = 0.8;
  const auto sh = make("seth_hill", {{"lambda", lambda}, {"mu", mu}, {"m", 2.0}});
  EXPECT_EQ(sh->domain(), Domain::All);
  for (const auto& s : samples(*sh)) {
    const Mat3 E = 0.5 * (s.F.transpose() * s.F - Mat3::Identity());
    const double psi = mu * E.squaredNorm() + 0.5 * lambda * E.trace() * E.trace();
    const Mat3 P = s.F * (2.0 * mu * E + lambda * E.trace() * Mat3::Identity());
    EXPECT_NEAR(sh->psi(s.F), psi, 1e-11 * std::max(1.0, psi)) << test::describe(s);
    EXPECT_LE(rel_error(sh->pk1(s.F), P, std::max(1.0, sh->hessian(s.F).norm())), 1e-10)
        << test::describe(s);
  }
  expect_derivatives_match(*sh, samples(*sh), "seth_hill m=2");
}

TEST(SethHill, OtherExponentsUnderFiniteDifferences) {
  for (double m : {3.0, 4.0, 0.5, -1.0, -2.5, 1.7}) {
    const auto sh = make("seth_hill", {{"lambda", 2.0}, {"mu", 0.7}, {"m", m}});
    const bool polynomial = m > 0 && m == std::round(m);
    EXPECT_EQ(sh->domain(), polynomial ? Domain::All : Domain::PositiveJ) << m;
    expect_derivatives_match(*sh, samples(*sh), "seth_hill m=" + std::to_string(m));
  }
}

TEST(SethHill, ZeroExponentIsRejected) {
  expect_error_containing([] { make("seth_hill", {{"m", 0.0}}); },
                          {"material 'seth_hill'", "parameter 'm'", "nonzero", "hencky"});
  expect_error_containing([] { make("symmetric_seth_hill", {{"m", 0.0}}); },
                          {"material 'symmetric_seth_hill'", "parameter 'm'", "nonzero"});
}

TEST(SymmetricSethHill, ExponentSignDoesNotMatterAndDerivativesMatch) {
  const auto a = make("symmetric_seth_hill", {{"lambda", 3.0}, {"mu", 1.1}, {"m", 1.5}});
  const auto b = make("symmetric_seth_hill", {{"lambda", 3.0}, {"mu", 1.1}, {"m", -1.5}});
  expect_same_material(*a, *b, samples(*a), "symmetric_seth_hill m vs -m");
  for (double m : {0.5, 2.0, 3.0}) {
    const auto s = make("symmetric_seth_hill", {{"lambda", 1.5}, {"mu", 0.6}, {"m", m}});
    expect_derivatives_match(*s, samples(*s), "symmetric_seth_hill m=" + std::to_string(m));
  }
}

TEST(Hencky, EqualsHillWithLogStrain) {
  const auto h = make("hencky", {{"lambda", 5.0}, {"mu", 2.0}});
  const auto hill = make("hill", {{"lambda", 5.0}, {"mu", 2.0}}, {{"f", "log(x)"}});
  expect_same_material(*h, *hill, samples(*h), "hencky vs hill(log)");
}

// ------------------------------------------------------------------- Hill family

TEST(Hill, StrainMeasuresReproduceOtherFamilies) {
  // f = x - 1: linear corotational; f = (x^2 - 1)/2: StVK (Seth-Hill m = 2).
  const auto lin = make("hill", {{"lambda", 2.0}, {"mu", 0.9}}, {{"f", "x - 1"}});
  const auto cr = make("linear_corotational", {{"lambda", 2.0}, {"mu", 0.9}});
  expect_same_material(*lin, *cr, samples(*lin), "hill(x-1) vs linear_corotational");
  const auto green = make("hill", {{"lambda", 2.0}, {"mu", 0.9}}, {{"f", "(x^2 - 1)/2"}});
  const auto stvk = make("seth_hill", {{"lambda", 2.0}, {"mu", 0.9}, {"m", 2.0}});
  expect_same_material(*green, *stvk, samples(*green), "hill((x^2-1)/2) vs seth_hill m=2");
}

TEST(Hill, NonDefaultStrainUnderFiniteDifferences) {
  for (const char* f : {"2*(sqrt(x) - 1)", "tanh(x - 1)", "(x - 1/x)/2", "sin(x-1) + mu*(x-1)^2"}) {
    const auto hill = make("hill", {{"lambda", 3.0}, {"mu", 1.2}}, {{"f", f}});
    expect_derivatives_match(*hill, samples(*hill), std::string("hill f=") + f);
    const Lame l = lame_from_energy(*hill);
    EXPECT_NEAR(l.lambda, 3.0, 1e-10) << f;
    EXPECT_NEAR(l.mu, 1.2, 1e-10) << f;
    EXPECT_LE(hill->pk1(Mat3::Identity()).norm(), 1e-12) << f;
  }
}

TEST(Hill, StrainMeasuresViolatingHillsConditionsAreRejected) {
  expect_error_containing([] { make("hill", {}, {{"f", "x"}}); },
                          {"material 'hill'", "function 'f'", "f(1) = 0 and f'(1) = 1", "f(1) = 1"});
  expect_error_containing([] { make("hill", {}, {{"f", "2*(x - 1)"}}); },
                          {"function 'f'", "f'(1) = 2"});
  expect_error_containing([] { make("hill", {}, {{"f", "log(y)"}}); },
                          {"material 'hill'", "function 'f'", "unknown identifier 'y'", "position 5"});
  expect_error_containing([] { make("hill", {}, {{"f", "log(x - 1)"}}); },
                          {"function 'f'", "not finite at x = 1"});
  expect_error_containing([] { make("hill", {}, {{"g", "x"}}); },
                          {"unknown function 'g'", "expected one of: f"});
}

// ------------------------------------------------------------------- Valanis-Landel family

TEST(ValanisLandel, OriginalIsShiftedToZeroEnergyAtRest) {
  const auto vl = make("valanis_landel", {{"lambda", 2.0}, {"mu", 1.5}});
  EXPECT_NEAR(vl->psi(Mat3::Identity()), 0.0, 1e-15);
  // Table form 2 mu sum s_i (log s_i - 1) + lambda/2 log^2 J, plus 6 mu.
  const Vec3 s(1.3, 0.8, 1.1);
  const double table = 2.0 * 1.5 * (s.array() * (s.array().log() - 1.0)).sum() +
                       0.5 * 2.0 * std::pow(std::log(s.prod()), 2);
  EXPECT_NEAR(vl->psi_stretch(s), table + 6.0 * 1.5, 1e-13);
  expect_derivatives_match(*vl, samples(*vl), "valanis_landel");
}

TEST(ValanisLandelNew, UserFunctionsUnderFiniteDifferences) {
  const auto vl = make("valanis_landel_new", {{"lambda", 3.0}, {"mu", 0.7}},
                       {{"f", "mu*(x-1)^2 + 0.3*(x-1)^3"}, {"h", "lambda/2*(x-1)^2 + 0.1*log(x)^4"}});
  expect_derivatives_match(*vl, samples(*vl), "valanis_landel_new");
  const Lame l = lame_from_energy(*vl);
  EXPECT_NEAR(l.lambda, 3.0, 1e-10);
  EXPECT_NEAR(l.mu, 0.7, 1e-10);
}

// With h'(1) != 0 the table's column no longer holds; the energy gives
// lambda_Lame = h''(1) + h'(1), mu_Lame = (f''(1) - h'(1))/2.
TEST(ValanisLandelNew, LameParametersWhenHPrimeIsNotZero) {
  const auto vl = make("valanis_landel_new", {{"lambda", 3.0}, {"mu", 0.7}},
                       {{"f", "mu*(x-1)^2 - 0.5*(x-1)"}, {"h", "0.5*(x-1) + lambda/2*(x-1)^2"}});
  EXPECT_LE(vl->pk1(Mat3::Identity()).norm(), 1e-14);
  const Lame l = lame_from_energy(*vl);
  EXPECT_NEAR(l.lambda, 3.0 + 0.5, 1e-12);
  EXPECT_NEAR(l.mu, (2.0 * 0.7 - 0.5) / 2.0, 1e-12);
  expect_derivatives_match(*vl, samples(*vl), "valanis_landel_new h'(1) != 0");
}

TEST(ValanisLandelNew, RestStressIsRejected) {
  expect_error_containing(
      [] { make("valanis_landel_new", {}, {{"f", "(x-1) + (x-1)^2"}, {"h", "log(x)^2"}}); },
      {"material 'valanis_landel_new'", "f'(1) + h'(1) = 0", "f'(1) = 1", "h'(1) = 0"});
  expect_error_containing([] { make("valanis_landel_new", {}, {{"h", "lambda*log(x"}}); },
                          {"function 'h'", "unbalanced parenthesis"});
}

// Xu's pair sum runs over the three unordered pairs i < j: with f = h = 0 and g = (x - 1)^2,
// Psi = (s0 s1 - 1)^2 + (s0 s2 - 1)^2 + (s1 s2 - 1)^2.
TEST(ValanisLandelXu, PairSumIsOverUnorderedPairs) {
  const auto xu = make("valanis_landel_xu", {}, {{"f", "0"}, {"g", "(x-1)^2"}, {"h", "0"}});
  const Vec3 s(1.4, 0.7, 1.2);
  const double want = std::pow(s(0) * s(1) - 1, 2) + std::pow(s(0) * s(2) - 1, 2) +
                      std::pow(s(1) * s(2) - 1, 2);
  EXPECT_NEAR(xu->psi_stretch(s), want, 1e-14);
  // Lame: g''(1) = 2 gives lambda_Lame = 2, mu_Lame = 1 (the table's g'' and g''/2).
  const Lame l = lame_from_energy(*xu);
  EXPECT_NEAR(l.lambda, 2.0, 1e-12);
  EXPECT_NEAR(l.mu, 1.0, 1e-12);
  expect_derivatives_match(*xu, samples(*xu), "valanis_landel_xu g only");
}

TEST(ValanisLandelXu, UserFunctionsUnderFiniteDifferences) {
  const auto xu = make("valanis_landel_xu", {{"lambda", 4.0}, {"mu", 0.5}},
                       {{"f", "mu/2*(x-1)^2 + 0.2*(x-1)^3"},
                        {"g", "0.3*(x-1)^2 + 0.2*(x-1)^3"},
                        {"h", "lambda/2*log(x)^2"}});
  expect_derivatives_match(*xu, samples(*xu), "valanis_landel_xu");
  // Table: lambda_Lame = g'' + h'' = 0.6 + 4, mu_Lame = (f'' + g'')/2 = (0.5 + 0.6)/2.
  const Lame l = lame_from_energy(*xu);
  EXPECT_NEAR(l.lambda, 4.6, 1e-12);
  EXPECT_NEAR(l.mu, 0.55, 1e-12);
}

// With g'(1) != 0: lambda_Lame = g'' + g' + h'' + h', mu_Lame = (f'' + g'' - g' - h')/2.
TEST(ValanisLandelXu, LameParametersWhenGPrimeIsNotZero) {
  const auto xu = make("valanis_landel_xu", {{"lambda", 4.0}, {"mu", 0.5}},
                       {{"f", "mu*(x-1)^2 - 0.4*(x-1)"}, {"g", "0.2*(x-1)"}, {"h", "lambda/2*log(x)^2"}});
  EXPECT_LE(xu->pk1(Mat3::Identity()).norm(), 1e-14);
  const Lame l = lame_from_energy(*xu);
  EXPECT_NEAR(l.lambda, 0.2 + 4.0, 1e-12);
  EXPECT_NEAR(l.mu, (2.0 * 0.5 - 0.2) / 2.0, 1e-12);
  expect_derivatives_match(*xu, samples(*xu), "valanis_landel_xu g'(1) != 0");
}

TEST(ValanisLandelXu, RestStressIsRejected) {
  expect_error_containing(
      [] { make("valanis_landel_xu", {}, {{"g", "(x-1)"}}); },
      {"material 'valanis_landel_xu'", "f'(1) + 2 g'(1) + h'(1) = 0", "g'(1) = 1"});
}

// ------------------------------------------------------------------- Ogden

TEST(Ogden, SeveralTermsUnderFiniteDifferences) {
  const auto three = make("ogden", {{"mu1", 1.3}, {"alpha1", 2.5}, {"mu2", -0.4}, {"alpha2", -1.5},
                                    {"mu3", 0.02}, {"alpha3", 6.0}});
  EXPECT_EQ(three->domain(), Domain::PositiveJ);
  expect_derivatives_match(*three, samples(*three), "ogden 3 terms");
  // The C++ class takes any number of terms; integer exponents are defined for every F.
  const Ogden five({0.5, -0.2, 0.1, 0.05, 0.0}, {2.0, 3.0, 1.0, 4.0, 0.0});
  EXPECT_EQ(five.domain(), Domain::All);
  expect_derivatives_match(five, samples(five), "ogden 5 integer terms");
  const Lame l = lame_from_energy(five);
  EXPECT_NEAR(l.lambda, 0.0, 1e-14);
  EXPECT_NEAR(l.mu, 0.5 * (0.5 * 1.0 - 0.2 * 2.0 + 0.1 * 0.0 + 0.05 * 3.0), 1e-13);
}

TEST(Ogden, RestStressIsTheSumOfCoefficients) {
  // P(I) = (sum_p mu_p) I: the family is not rest-stable in general, only when the mu_p sum to 0.
  const auto o = make("ogden", {{"mu1", 1.0}, {"alpha1", 2.0}, {"mu2", 0.5}, {"alpha2", -2.0},
                                {"mu3", 0.0}});
  EXPECT_LE((o->pk1(Mat3::Identity()) - 1.5 * Mat3::Identity()).norm(), 1e-14);
  EXPECT_FALSE(MaterialCatalog::instance().find("ogden").rest_stable);
  const auto defaults = make("ogden");
  EXPECT_LE(defaults->pk1(Mat3::Identity()).norm(), 1e-14);  // the defaults sum to 0
  EXPECT_NEAR(lame_from_energy(*defaults).mu, 1.0, 1e-12);
}

TEST(Ogden, InvalidTermsAreRejected) {
  expect_error_containing([] { make("ogden", {{"alpha2", 0.0}}); },
                          {"material 'ogden'", "parameter 'alpha2'", "nonzero exponent"});
  EXPECT_NO_THROW(make("ogden", {{"mu3", 0.0}, {"alpha3", 0.0}}));  // inactive term
  expect_error_containing([] { Ogden({1.0, 2.0}, {2.0}); }, {"2 coefficients", "1 exponents"});
}

// ------------------------------------------------------------------- Mooney-Rivlin

TEST(MooneyRivlin, LiteralReadingLameAndRestStress) {
  const double C1 = 0.8, C2 = 0.3;
  const auto mr = make("mooney_rivlin", {{"C1", C1}, {"C2", C2}});
  // Written independently: C1 J^-2/3 (I1 - 3) + C2 J^-4/3 (I2 - 3).
  const Vec3 s(1.2, 0.9, 1.05);
  const double J = s.prod();
  const double I1 = s.squaredNorm();
  const double I2 = s(0) * s(0) * s(1) * s(1) + s(1) * s(1) * s(2) * s(2) + s(2) * s(2) * s(0) * s(0);
  EXPECT_NEAR(mr->psi_stretch(s),
              C1 * std::pow(J, -2.0 / 3.0) * (I1 - 3.0) + C2 * std::pow(J, -4.0 / 3.0) * (I2 - 3.0),
              1e-14);
  const Lame l = lame_from_energy(*mr);
  EXPECT_NEAR(l.lambda, -4.0 / 3.0 * (2.0 * C1 + 5.0 * C2), 1e-12);
  EXPECT_NEAR(l.mu, C1, 1e-12);
  // P(I) = (2 C1 + 4 C2) I: rest-stable only for C2 = -C1/2 (the defaults).
  EXPECT_LE((mr->pk1(Mat3::Identity()) - (2.0 * C1 + 4.0 * C2) * Mat3::Identity()).norm(), 1e-13);
  EXPECT_LE(make("mooney_rivlin")->pk1(Mat3::Identity()).norm(), 1e-14);
  expect_derivatives_match(*mr, samples(*mr), "mooney_rivlin");
}

// ------------------------------------------------------------------- other families

TEST(Table1Families, NonDefaultParametersUnderFiniteDifferences) {
  const std::vector<std::pair<std::string, std::map<std::string, double>>> cases = {
      {"hencky", {{"lambda", 7.0}, {"mu", 0.3}}},
      {"neo_hookean", {{"lambda", 9.0}, {"mu", 2.0}}},
      {"neo_hookean_ogden", {{"lambda", 9.0}, {"mu", 2.0}}},
      {"sts", {{"lambda", 2.0}, {"mu", 0.5}, {"mu4", 2.0}}},
      {"peng_landel", {{"E", 7.5}}},
      {"arap", {{"mu", 2.5}}},
      {"symmetric_arap", {{"mu", 2.5}}},
      {"symmetric_dirichlet", {{"mu", 0.4}}},
      {"valanis_landel", {{"lambda", 6.0}, {"mu", 0.2}}},
  };
  for (const auto& [name, values] : cases) {
    const auto m = make(name, values);
    expect_derivatives_match(*m, samples(*m, 5u), name);
  }
}

TEST(Table1Families, PositiveJFamiliesRejectInvertedF) {
  const Mat3 inverted = Vec3(1.2, 0.9, -0.4).asDiagonal();
  for (const char* name :
       {"hencky", "symmetric_seth_hill", "hill", "neo_hookean", "neo_hookean_ogden", "sts",
        "valanis_landel", "valanis_landel_new", "valanis_landel_xu", "peng_landel",
        "symmetric_arap", "symmetric_dirichlet", "ogden", "mooney_rivlin"}) {
    const auto m = make(name);
    EXPECT_EQ(m->domain(), Domain::PositiveJ) << name;
    expect_error_containing([&] { m->pk1(inverted); }, {name, "J = det F > 0"});
  }
  EXPECT_EQ(make("seth_hill", {{"m", 0.5}})->domain(), Domain::PositiveJ);
  for (const char* name : {"arap", "seth_hill", "linear_corotational"}) {
    const auto m = make(name);
    EXPECT_EQ(m->domain(), Domain::All) << name;
    EXPECT_TRUE(std::isfinite(m->psi(inverted))) << name;
  }
}

TEST(Table1Families, ScaleParametersReproduceTheTable) {
  // ARAP mu = 1: sum (s_i - 1)^2; symmetric Dirichlet mu = 1: 1/2 sum (s_i - 1/s_i)^2.
  const Vec3 s(1.3, 0.6, 2.1);
  EXPECT_NEAR(make("arap")->psi_stretch(s), (s.array() - 1.0).square().sum(), 1e-14);
  EXPECT_NEAR(make("symmetric_dirichlet")->psi_stretch(s),
              0.5 * (s.array() - s.array().inverse()).square().sum(), 1e-14);
  EXPECT_NEAR(make("symmetric_arap", {{"mu", 2.0}})->psi_stretch(s),
              ((s.array() - 1.0).square() + (1.0 - s.array().inverse()).square()).sum(), 1e-14);
}

// ------------------------------------------------------------------- divided differences

TEST(DividedDifferences, MatchQuotientsAndLimits) {
  using namespace table1;
  for (double n : {-3.0, -2.0, -1.0, 0.0, 1.0, 2.0, 3.0, 7.0, 0.5, -1.5, 2.7}) {
    for (auto [x, y] : {std::pair{1.7, 0.6}, std::pair{0.3, 2.2}, std::pair{1.25, 1.25}}) {
      const double flip = x == y ? n * std::pow(x, n - 1.0)
                                 : (std::pow(x, n) - std::pow(y, n)) / (x - y);
      EXPECT_NEAR(power_flip(x, y, n), flip, 1e-13 * std::max(1.0, std::abs(flip))) << n;
      const double twist = (std::pow(x, n) + std::pow(y, n)) / (x + y);
      EXPECT_NEAR(power_twist(x, y, n), twist, 1e-13 * std::max(1.0, std::abs(twist))) << n;
    }
    // Nearly equal arguments: the quotient tends to the derivative without cancellation.
    const double x = 1.3, y = x * (1.0 + 1e-12);
    EXPECT_NEAR(power_flip(x, y, n), n * std::pow(x, n - 1.0), 1e-10 * std::max(1.0, std::abs(n)));
  }
  // Odd integer powers have a regular twist quotient at y = -x: (x^3 + y^3)/(x + y) =
  // x^2 - x y + y^2, and (1/x + 1/y)/(x + y) = 1/(x y).
  EXPECT_NEAR(power_twist(0.8, -0.8, 3.0), 3.0 * 0.8 * 0.8, 1e-15);
  EXPECT_NEAR(power_twist(0.8, -0.8, -1.0), -1.0 / (0.8 * 0.8), 1e-14);
  // Signed integer flips.
  EXPECT_NEAR(power_flip(-0.5, 1.5, 3.0), ((-0.125) - 3.375) / (-2.0), 1e-15);
  EXPECT_NEAR(log_flip(2.0, 0.5), (std::log(2.0) - std::log(0.5)) / 1.5, 1e-15);
  EXPECT_NEAR(log_flip(1.5, 1.5 * (1 + 1e-13)), 1.0 / 1.5, 1e-12);
}

}  // namespace
}  // namespace sinew
