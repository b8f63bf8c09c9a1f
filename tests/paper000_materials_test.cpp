// Paper 000's material families beyond the shared catalog test: Lamé reparameterisation (§3.4),
// the co-rotational alias, Kikuuwe's compression term, the Fung and Arruda-Boyce extensions
// (§5.3), the filtered Neo-Hookean baseline (§6), and derivatives at non-default parameters.
#include <gtest/gtest.h>

#include <cmath>

#include "material_test_support.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/svd.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/material/lame.hpp"
#include "sinew/material/families.hpp"

namespace sinew {
namespace {

// Relative error, absolute below 1: stresses vanish at rest, where the comparisons are rounding.
template <class A, class B>
double rel_error(const A& a, const B& b) {
  return test::rel_error(a, b, 1.0);
}

std::unique_ptr<Material> make(const std::string& name, std::map<std::string, double> values) {
  MaterialParameters p;
  p.values = std::move(values);
  return MaterialCatalog::instance().make(name, p);
}

Mat3 inverse_transpose(const Mat3& F) { return F.inverse().transpose(); }

// ---------------------------------------------------------------- §3.4 Lamé reparameterisation

TEST(Paper000Lame, StableNeoHookeanEq14) {
  for (auto [lambda, mu] : {std::pair{10.0, 1.0}, {0.7, 2.0}, {1000.0, 3.0}}) {
    const Lame l = lame_from_energy(*make("stable_neo_hookean", {{"lambda", lambda}, {"mu", mu}}));
    EXPECT_NEAR(l.lambda, lambda - 5.0 / 8.0 * mu, 1e-12 * lambda);
    EXPECT_NEAR(l.mu, 0.75 * mu, 1e-12 * mu);
    // Eq. 16: nu = (lambda - 5/8 mu) / (2 (lambda + 1/8 mu)).
    EXPECT_NEAR(young_poisson(l).nu, (lambda - 0.625 * mu) / (2.0 * (lambda + 0.125 * mu)), 1e-12);
  }
  // Normalising to given Lamé parameters: mu = 4/3 mu_L, lambda = lambda_L + 5/6 mu_L.
  for (auto [lambda_L, mu_L] : {std::pair{5.0, 1.0}, {0.0, 2.0}, {48.0, 0.5}}) {
    const Lame l = lame_from_energy(*make(
        "stable_neo_hookean", {{"lambda", lambda_L + 5.0 / 6.0 * mu_L}, {"mu", 4.0 / 3.0 * mu_L}}));
    EXPECT_NEAR(l.lambda, lambda_L, 1e-12 * (1.0 + lambda_L));
    EXPECT_NEAR(l.mu, mu_L, 1e-12 * mu_L);
  }
}

TEST(Paper000Lame, StableNeoHookeanEq13) {
  for (auto [lambda, mu] : {std::pair{10.0, 1.0}, {0.7, 2.0}, {1000.0, 3.0}}) {
    const Lame l = lame_from_energy(*make("stable_neo_hookean_eq13", {{"lambda", lambda}, {"mu", mu}}));
    EXPECT_NEAR(l.lambda, lambda - mu, 1e-12 * lambda);
    EXPECT_NEAR(l.mu, mu, 1e-12 * mu);
    EXPECT_NEAR(young_poisson(l).nu, (lambda - mu) / (2.0 * lambda), 1e-12);  // §3.4
  }
  for (auto [lambda_L, mu_L] : {std::pair{5.0, 1.0}, {0.0, 2.0}, {48.0, 0.5}}) {
    const Lame l = lame_from_energy(
        *make("stable_neo_hookean_eq13", {{"lambda", lambda_L + mu_L}, {"mu", mu_L}}));
    EXPECT_NEAR(l.lambda, lambda_L, 1e-12 * (1.0 + lambda_L));
    EXPECT_NEAR(l.mu, mu_L, 1e-12 * mu_L);
  }
}

TEST(Paper000Lame, OtherFamilies) {
  auto expect = [](const Material& m, double lambda_L, double mu_L) {
    const Lame l = lame_from_energy(m);
    EXPECT_NEAR(l.lambda, lambda_L, 1e-12 * (1.0 + std::abs(lambda_L))) << m.name();
    EXPECT_NEAR(l.mu, mu_L, 1e-12 * (1.0 + std::abs(mu_L))) << m.name();
  };
  expect(*make("corotational", {{"lambda", 3.0}, {"mu", 0.5}}), 3.0, 0.5);
  expect(*make("fixed_corotational", {{"lambda", 3.0}, {"mu", 0.5}}), 3.0, 0.5);
  expect(*make("stvk", {{"lambda", 3.0}, {"mu", 0.5}}), 3.0, 0.5);
  expect(*make("stvk_kikuuwe", {{"lambda", 3.0}, {"mu", 0.5}, {"kappa", 1e4}}), 3.0, 0.5);
  expect(*make("neo_hookean_filtered", {{"lambda", 3.0}, {"mu", 0.5}}), 3.0, 0.5);
  const double mu0 = 0.8, mu1 = 0.3, gamma = 2.0, lambda = 7.0;
  expect(*make("fung", {{"mu0", mu0}, {"mu1", mu1}, {"gamma", gamma}, {"lambda", lambda}}),
         lambda + gamma * mu1 * mu1 - mu0 - gamma * mu1, mu0 + gamma * mu1);
  const double mu = 1.5, b1 = 0.2, b2 = 0.03;
  expect(*make("arruda_boyce", {{"lambda", lambda}, {"mu", mu}, {"beta1", b1}, {"beta2", b2}}),
         lambda + 2.0 * mu * (b1 + 6.0 * b2) - mu * (1.0 + 3.0 * b1 + 9.0 * b2),
         mu * (1.0 + 3.0 * b1 + 9.0 * b2));
}

TEST(Paper000Catalog, FlagsAndNames) {
  const auto& catalog = MaterialCatalog::instance();
  const std::map<std::string, bool> separable = {
      {"stable_neo_hookean", false}, {"stable_neo_hookean_eq13", true},
      {"corotational", true},        {"fixed_corotational", true},
      {"stvk", true},                {"stvk_kikuuwe", false},
      {"fung", false},               {"arruda_boyce", false},
      {"neo_hookean_filtered", true}};
  for (const auto& [name, sep] : separable) {
    const MaterialInfo& info = catalog.find(name);
    EXPECT_EQ(info.separable, sep) << name;
    EXPECT_TRUE(info.rest_stable) << name;
    const std::vector<std::string> normalized =
        name == "fung" ? std::vector<std::string>{"lambda", "mu0"}
                       : std::vector<std::string>{"lambda", "mu"};
    EXPECT_EQ(info.normalized, normalized) << name;
    EXPECT_EQ(catalog.make(name)->name(), name);
    // Defaults give a physically sensible material: mu_Lame > 0 and lambda_Lame > 0.
    const Lame l = lame_from_energy(*catalog.make(name));
    EXPECT_GT(l.mu, 0.0) << name;
    EXPECT_GT(l.lambda, 0.0) << name;
  }
}

TEST(Paper000Catalog, InvalidParametersAreErrors) {
  EXPECT_THROW(make("stable_neo_hookean", {{"lambda", 0.0}}), Error);
  EXPECT_THROW(make("fung", {{"lambda", 0.0}}), Error);
  EXPECT_THROW(make("arruda_boyce", {{"lambda", 0.0}}), Error);
  EXPECT_THROW(make("neo_hookean_filtered", {{"threshold", 0.0}}), Error);
  EXPECT_THROW(make("neo_hookean_filtered", {{"threshold", 1.0}}), Error);
  try {
    make("neo_hookean_filtered", {{"threshold", -0.5}});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("threshold"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("neo_hookean_filtered"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------- comparison models

TEST(Paper000Models, CorotationalIsLinearCorotational) {
  const auto a = make("corotational", {{"lambda", 4.0}, {"mu", 0.7}});
  const auto b = make("linear_corotational", {{"lambda", 4.0}, {"mu", 0.7}});
  for (const auto& s : test::sample_set(5u, 5, true)) {
    EXPECT_NEAR(a->psi(s.F), b->psi(s.F), 1e-14 * (1.0 + std::abs(b->psi(s.F))));
    EXPECT_LE(rel_error(a->pk1(s.F), b->pk1(s.F)), 1e-14);
    EXPECT_LE(rel_error(a->hessian(s.F), b->hessian(s.F)), 1e-14);
  }
}

TEST(Paper000Models, FixedCorotationalIsEq49) {
  const double lambda = 4.0, mu = 0.7;
  const auto m = make("fixed_corotational", {{"lambda", lambda}, {"mu", mu}});
  for (const auto& s : test::sample_set(6u, 5, true)) {
    const Mat3 R = polar_rotation(s.F);
    const double J = s.F.determinant();
    const double psi = mu * (s.F - R).squaredNorm() + 0.5 * lambda * (J - 1.0) * (J - 1.0);
    EXPECT_NEAR(m->psi(s.F), psi, 1e-12 * (1.0 + psi)) << test::describe(s);
  }
}

TEST(Paper000Models, StvkIsEq50) {
  const double lambda = 4.0, mu = 0.7;
  const auto m = make("stvk", {{"lambda", lambda}, {"mu", mu}});
  for (const auto& s : test::sample_set(7u, 5, true)) {
    const Mat3 E = 0.5 * (s.F.transpose() * s.F - Mat3::Identity());
    const double psi = mu * E.squaredNorm() + 0.5 * lambda * E.trace() * E.trace();
    EXPECT_NEAR(m->psi(s.F), psi, 1e-12 * (1.0 + psi)) << test::describe(s);
    const Mat3 P = s.F * (2.0 * mu * E + lambda * E.trace() * Mat3::Identity());  // F S
    EXPECT_LE(rel_error(m->pk1(s.F), P), 1e-12) << test::describe(s);
  }
}

TEST(Paper000Models, KikuuweEqualsStvkInExtensionAndAddsTheCubicInCompression) {
  const double lambda = 4.0, mu = 0.7, kappa = 5000.0;
  const auto k = make("stvk_kikuuwe", {{"lambda", lambda}, {"mu", mu}, {"kappa", kappa}});
  const auto s = make("stvk", {{"lambda", lambda}, {"mu", mu}});
  std::mt19937 rng(8);
  int extended = 0, compressed = 0;
  for (const auto& x : test::sample_set(9u, 8, true)) {
    const double J = x.F.determinant();
    if (J >= 1.0) {
      ++extended;
      EXPECT_EQ(k->psi(x.F), s->psi(x.F));
      EXPECT_LE(rel_error(k->pk1(x.F), s->pk1(x.F)), 1e-14);
      EXPECT_LE(rel_error(k->hessian(x.F), s->hessian(x.F)), 1e-13);
    } else {
      ++compressed;
      const double term = kappa / 12.0 * std::pow((1.0 - J) / 6.0, 3);  // Eq. 51
      EXPECT_NEAR(k->psi(x.F) - s->psi(x.F), term, 1e-10 * (1.0 + term));
      // P of the term: c'(J) dJ/dF.
      const Mat3 dP = -3.0 * kappa / 12.0 / 216.0 * (1.0 - J) * (1.0 - J) * cofactor(x.F);
      EXPECT_LE(rel_error(k->pk1(x.F) - s->pk1(x.F), dP), 1e-10);
    }
  }
  EXPECT_GT(extended, 5);
  EXPECT_GT(compressed, 5);
}

TEST(Paper000Models, KikuuweIsC2AcrossJEqualsOne) {
  const double kappa = 5e4;
  const auto k = make("stvk_kikuuwe", {{"lambda", 4.0}, {"mu", 0.7}, {"kappa", kappa}});
  const auto s = make("stvk", {{"lambda", 4.0}, {"mu", 0.7}});
  std::mt19937 rng(10);
  const Mat3 R1 = test::random_rotation(rng), R2 = test::random_rotation(rng);
  // F(t) with J = 1 + t; the compression term's P and Hessian must vanish as t -> 0-, like
  // t^2 and t, so both are continuous across J = 1 (the third derivative is not).
  auto F = [&](double t) { return Mat3(R1 * Vec3(1.2, 1.0 / 1.2, 1.0 + t).asDiagonal() * R2); };
  double previous_P = 0.0, previous_H = 0.0;
  for (double t : {1e-2, 1e-3, 1e-4}) {
    const double dP = (k->pk1(F(-t)) - s->pk1(F(-t))).norm();
    const double dH = (k->hessian(F(-t)) - s->hessian(F(-t))).norm();
    EXPECT_EQ((k->pk1(F(t)) - s->pk1(F(t))).norm(), 0.0);
    EXPECT_EQ((k->hessian(F(t)) - s->hessian(F(t))).norm(), 0.0);
    if (previous_P > 0.0) {
      EXPECT_NEAR(previous_P / dP, 100.0, 5.0);  // ~ t^2
      EXPECT_NEAR(previous_H / dH, 10.0, 0.5);   // ~ t: continuous, not C3
    }
    previous_P = dP;
    previous_H = dH;
  }
}

// ---------------------------------------------------------------- §5.3 extensions

TEST(Paper000Extensions, FungPk1IsEq54AndRestStable) {
  for (auto [mu0, mu1, gamma, lambda] :
       {std::tuple{1.0, 0.1, 1.0, 10.0}, {0.5, 0.4, 2.0, 3.0}, {2.0, 1.0, 0.3, 100.0}}) {
    const auto m = make("fung", {{"mu0", mu0}, {"mu1", mu1}, {"gamma", gamma}, {"lambda", lambda}});
    const double alpha = 1.0 + (mu0 + gamma * mu1) / lambda;
    for (const auto& s : test::sample_set(11u, 3, true)) {
      const double Ic = s.F.squaredNorm(), J = s.F.determinant();
      const double e = std::exp(0.5 * mu1 * (Ic - 3.0));
      const Mat3 P = mu0 * s.F + lambda * (J - alpha) * cofactor(s.F) + gamma * mu1 * e * s.F;
      EXPECT_LE(rel_error(m->pk1(s.F), P), 1e-12) << test::describe(s);
      const double psi = 0.5 * mu0 * (Ic - 3.0) + 0.5 * lambda * (J - alpha) * (J - alpha) +
                         gamma * (e - 1.0) -  // Eq. 53 in the form chosen (docs)
                         0.5 * lambda * (1.0 - alpha) * (1.0 - alpha);  // shifted: Psi(I) = 0
      EXPECT_NEAR(m->psi(s.F), psi, 1e-11 * (1.0 + std::abs(psi)));
    }
    std::mt19937 rng(12);
    EXPECT_LE(m->pk1(Mat3::Identity()).norm(), 1e-13);
    EXPECT_LE(m->pk1(test::random_rotation(rng)).norm(), 1e-12);
  }
}

TEST(Paper000Extensions, FungHessianHasThePapersConstantsExceptEq55sFactorTwo) {
  const double mu0 = 0.5, mu1 = 0.4, gamma = 2.0, lambda = 3.0;
  const auto m = make("fung", {{"mu0", mu0}, {"mu1", mu1}, {"gamma", gamma}, {"lambda", lambda}});
  const double alpha = 1.0 + (mu0 + gamma * mu1) / lambda;
  for (const auto& s : test::sample_set(13u, 3, true)) {
    const double Ic = s.F.squaredNorm(), J = s.F.determinant();
    const double e = std::exp(0.5 * mu1 * (Ic - 3.0));
    const Vec9 f = vec(s.F), g = vec(cofactor(s.F));
    // Eq. 55 with mu_T from Eq. 56; the f f^T coefficient is what Psi's second I_C derivative
    // gives, gamma mu1^2 e: half of Eq. 55's printed 2 gamma mu1^2 e.
    const Mat9 H = (mu0 + gamma * mu1 * e) * Mat9::Identity() + lambda * g * g.transpose() +
                   lambda * (J - alpha) * volume_hessian(s.F) + gamma * mu1 * mu1 * e * f * f.transpose();
    EXPECT_LE(rel_error(m->hessian(s.F), H), 1e-12) << test::describe(s);
    EXPECT_LE(rel_error(test::fd_hessian(*m, s.F), H), 1e-6) << test::describe(s);
    const Eigensystem es = m->eigensystem(s.F);
    const SignedSvd svd = signed_svd(s.F);
    for (int k = 0; k < 3; ++k) {  // Eq. 46-48 with Eq. 56: mu_T +- lambda (J - alpha) sigma_k
      EXPECT_NEAR(es.values(3 + k), mu0 + gamma * mu1 * e + lambda * (J - alpha) * svd.sigma(k),
                  1e-12 * H.norm());
      EXPECT_NEAR(es.values(6 + k), mu0 + gamma * mu1 * e - lambda * (J - alpha) * svd.sigma(k),
                  1e-12 * H.norm());
    }
  }
}

TEST(Paper000Extensions, ArrudaBoyceIsEq58To61AndRestStable) {
  for (auto [lambda, mu, b1, b2] :
       {std::tuple{10.0, 1.0, 0.1, 0.01}, {3.0, 0.5, 0.5, 0.1}, {100.0, 2.0, 0.02, 0.3}}) {
    const auto m = make("arruda_boyce", {{"lambda", lambda}, {"mu", mu}, {"beta1", b1}, {"beta2", b2}});
    const double alpha = 1.0 + mu / lambda * (1.0 + 3.0 * b1 + 9.0 * b2);
    for (const auto& s : test::sample_set(14u, 3, true)) {
      const double Ic = s.F.squaredNorm(), J = s.F.determinant();
      const double psi = 0.5 * mu * (Ic - 3.0) + mu * b1 / 4.0 * (Ic * Ic - 9.0) +
                         mu * b2 / 6.0 * (Ic * Ic * Ic - 27.0) + 0.5 * lambda * (J - alpha) * (J - alpha) -
                         0.5 * lambda * (1.0 - alpha) * (1.0 - alpha);  // shifted: Psi(I) = 0
      EXPECT_NEAR(m->psi(s.F), psi, 1e-11 * (1.0 + std::abs(psi)));
      const Mat3 P = mu * (1.0 + b1 * Ic + b2 * Ic * Ic) * s.F + lambda * (J - alpha) * cofactor(s.F);
      EXPECT_LE(rel_error(m->pk1(s.F), P), 1e-12);  // Eq. 59
      const Vec9 f = vec(s.F), g = vec(cofactor(s.F));
      const Mat9 H = mu * (1.0 + b1 * Ic + b2 * Ic * Ic) * Mat9::Identity() + lambda * g * g.transpose() +
                     lambda * (J - alpha) * volume_hessian(s.F) +
                     2.0 * mu * (b1 + 2.0 * b2 * Ic) * f * f.transpose();  // Eq. 60
      EXPECT_LE(rel_error(m->hessian(s.F), H), 1e-12);
    }
    std::mt19937 rng(15);
    EXPECT_LE(m->pk1(Mat3::Identity()).norm(), 1e-12);
    EXPECT_LE(m->pk1(test::random_rotation(rng)).norm(), 1e-11);
  }
}

TEST(Paper000Extensions, WithoutHardeningBothReduceToEq13) {
  const double lambda = 6.0, mu = 1.3;
  const auto eq13 = make("stable_neo_hookean_eq13", {{"lambda", lambda}, {"mu", mu}});
  const auto fung = make("fung", {{"mu0", mu}, {"mu1", 0.7}, {"gamma", 0.0}, {"lambda", lambda}});
  const auto ab = make("arruda_boyce", {{"lambda", lambda}, {"mu", mu}, {"beta1", 0.0}, {"beta2", 0.0}});
  // lambda/2 (J - alpha)^2 = lambda/2 (J - 1)^2 - mu (J - 1) + mu^2 / (2 lambda); the constant
  // is removed (every energy is shifted to Psi(I) = 0).
  const double constant = 0.0;
  for (const auto& s : test::sample_set(16u, 4, true)) {
    for (const Material* m : {fung.get(), ab.get()}) {
      EXPECT_NEAR(m->psi(s.F) - eq13->psi(s.F), constant, 1e-11 * (1.0 + std::abs(eq13->psi(s.F))));
      EXPECT_LE(rel_error(m->pk1(s.F), eq13->pk1(s.F)), 1e-13) << m->name();
      EXPECT_LE(rel_error(m->hessian(s.F), eq13->hessian(s.F)), 1e-13) << m->name();
      Vec9 a = m->eigensystem(s.F).values, b = eq13->eigensystem(s.F).values;
      std::sort(a.data(), a.data() + 9);
      std::sort(b.data(), b.data() + 9);
      EXPECT_LE((a - b).norm(), 1e-12 * (1.0 + b.norm())) << m->name();
    }
  }
}

// ---------------------------------------------------------------- filtered Neo-Hookean

// The unfiltered Neo-Hookean energy, Eq. 5, and its PK1 mu (F - F^-T) + lambda log J F^-T.
double neo_hookean_psi(const Mat3& F, double lambda, double mu) {
  const double logJ = std::log(F.determinant());
  return 0.5 * mu * (F.squaredNorm() - 3.0) - mu * logJ + 0.5 * lambda * logJ * logJ;
}
Mat3 neo_hookean_pk1(const Mat3& F, double lambda, double mu) {
  return mu * (F - inverse_transpose(F)) + lambda * std::log(F.determinant()) * inverse_transpose(F);
}

TEST(Paper000Filtered, EqualsNeoHookeanAboveTheThreshold) {
  const double lambda = 7.0, mu = 0.5, c = 0.3;
  const auto m = make("neo_hookean_filtered", {{"lambda", lambda}, {"mu", mu}, {"threshold", c}});
  int checked = 0;
  for (const auto& s : test::sample_set(17u, 10, false)) {
    if (s.sigma.minCoeff() <= c) continue;
    ++checked;
    const double psi = neo_hookean_psi(s.F, lambda, mu);
    EXPECT_NEAR(m->psi(s.F), psi, 1e-11 * (1.0 + std::abs(psi))) << test::describe(s);
    EXPECT_LE(rel_error(m->pk1(s.F), neo_hookean_pk1(s.F, lambda, mu)), 1e-11) << test::describe(s);
    // The Hessian against central differences of the formula's P.
    Mat9 H;
    const double h = 1e-6;
    for (int k = 0; k < 9; ++k) {
      Mat3 Fp = s.F, Fm = s.F;
      Fp(k % 3, k / 3) += h;
      Fm(k % 3, k / 3) -= h;
      H.col(k) = vec(neo_hookean_pk1(Fp, lambda, mu) - neo_hookean_pk1(Fm, lambda, mu)) / (2.0 * h);
    }
    EXPECT_LE(rel_error(m->hessian(s.F), H), 1e-7) << test::describe(s);
  }
  EXPECT_GE(checked, 30);
}

TEST(Paper000Filtered, FilterIsC2AndExtrapolatesTheStressLinearly) {
  const double c = 0.25;
  const NeoHookeanFiltered m(7.0, 0.5, c, -1e-4);
  // Across s = c the changes are those of a C2 function (only the third derivative jumps): value
  // and slope change by their smooth increments, the curvature by O(d) only.
  const double d = 1e-6;
  EXPECT_NEAR(m.log_filtered(c + d) - m.log_filtered(c - d), 2.0 * d / c, 1e-12);
  EXPECT_NEAR(m.log_filtered_d(c + d) - m.log_filtered_d(c - d), -2.0 * d / (c * c), 1e-9);
  EXPECT_NEAR(m.log_filtered_dd(c + d), m.log_filtered_dd(c - d), 1e-3);
  EXPECT_NEAR(m.log_filtered_dd(c - d), -1.0 / (c * c), 1e-12);
  EXPECT_DOUBLE_EQ(m.log_filtered_dd(0.1), m.log_filtered_dd(-0.7));  // constant curvature below c
  EXPECT_GT(m.log_filtered_d(-2.0), 0.0);  // increasing for every s < 2c: no spurious extremum
  // Inverted and collapsed elements get finite energy and stress that push back to J > 0.
  for (const Mat3& F : {Mat3(Vec3(1.0, 1.0, -0.5).asDiagonal()), Mat3(Mat3::Zero())}) {
    EXPECT_TRUE(std::isfinite(m.psi(F)));
    EXPECT_TRUE(m.pk1(F).allFinite());
  }
  EXPECT_LT(m.pk1(Vec3(1.0, 1.0, -0.5).asDiagonal())(2, 2), 0.0);  // dPsi/dsigma_2 < 0: expand
}

TEST(Paper000Filtered, ClampUsesTheHessianThreshold) {
  const double floor = -1e-3;
  const auto m = make("neo_hookean_filtered", {{"hessian_threshold", floor}});
  EXPECT_EQ(m->projection_floor(), floor);
  int indefinite = 0;
  for (const auto& s : test::sample_set(18u, 10, true)) {
    const Mat9 H = m->hessian(s.F);
    const Vec9 before = test::numeric_eigenvalues(H);
    if (before.minCoeff() >= floor) continue;
    ++indefinite;
    const Vec9 after = test::numeric_eigenvalues(m->projected_hessian(s.F, Projection::Clamp));
    EXPECT_NEAR(after.minCoeff(), floor, 1e-9 * H.norm()) << test::describe(s);
  }
  EXPECT_GT(indefinite, 5);
}

// ---------------------------------------------------------------- derivatives off the defaults

struct Family {
  std::string name;
  std::map<std::string, double> values;
};

TEST(Paper000Derivatives, FiniteDifferencesAtNonDefaultParameters) {
  const Family families[] = {
      {"stable_neo_hookean", {{"lambda", 3.0}, {"mu", 2.5}}},
      {"stable_neo_hookean", {{"lambda", 0.15}, {"mu", 1.0}}},
      {"stable_neo_hookean_eq13", {{"lambda", 50.0}, {"mu", 0.3}}},
      {"corotational", {{"lambda", 2.0}, {"mu", 0.4}}},
      {"fixed_corotational", {{"lambda", 2.0}, {"mu", 3.0}}},
      {"stvk", {{"lambda", 0.5}, {"mu", 2.0}}},
      {"stvk_kikuuwe", {{"lambda", 4.0}, {"mu", 1.0}, {"kappa", 5000.0}}},
      {"fung", {{"mu0", 0.5}, {"mu1", 0.3}, {"gamma", 2.0}, {"lambda", 20.0}}},
      {"arruda_boyce", {{"lambda", 5.0}, {"mu", 0.7}, {"beta1", 0.3}, {"beta2", 0.05}}},
      {"neo_hookean_filtered",
       {{"lambda", 7.0}, {"mu", 0.5}, {"threshold", 0.4}, {"hessian_threshold", -1e-3}}}};
  for (const Family& f : families) {
    const auto m = make(f.name, f.values);
    for (const auto& s : test::sample_set(19u, 4, true)) {
      // Kikuuwe's term is C2 only at J = 1, where central differences of P lose their order.
      if (f.name == "stvk_kikuuwe" && std::abs(s.F.determinant() - 1.0) < 1e-2) continue;
      EXPECT_LE(rel_error(m->pk1(s.F), test::fd_pk1(*m, s.F)), 1e-6) << f.name << " " << test::describe(s);
      const Mat9 H = m->hessian(s.F);
      EXPECT_LE(rel_error(H, test::fd_hessian(*m, s.F)), 1e-6) << f.name << " " << test::describe(s);
      const Eigensystem es = m->eigensystem(s.F);
      const double scale = std::max(1.0, H.norm());
      for (int k = 0; k < 9; ++k) {
        EXPECT_LE((H * es.vectors.col(k) - es.values(k) * es.vectors.col(k)).norm() / scale, 1e-9)
            << f.name << " " << test::describe(s) << " eigenpair " << k;
      }
      const Evaluation e = m->evaluate(s.F, Projection::Abs);
      EXPECT_LE(rel_error(e.hessian, m->projected_hessian(s.F, Projection::Abs)), 1e-10) << f.name;
      EXPECT_LE(rel_error(e.P, m->pk1(s.F)), 1e-12) << f.name;
    }
  }
}

}  // namespace
}  // namespace sinew
