// The nonlinearity exponent psi_alpha(s) = psi(s^alpha) / alpha^2 (paper 002 Eq. 16-18),
// wrapped around every catalog family.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "material_battery.hpp"
#include "sinew/core/error.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/material/families/corotational.hpp"
#include "sinew/material/lame.hpp"
#include "sinew/material/nonlinearity.hpp"

namespace sinew {
namespace {

std::vector<std::string> all_names() {
  std::vector<std::string> names;
  for (const auto& f : MaterialCatalog::instance().all()) names.push_back(f.name);
  return names;
}

std::shared_ptr<const Material> family(const std::string& name) {
  return MaterialCatalog::instance().make(name);
}

class NonlinearEveryFamily : public ::testing::TestWithParam<std::string> {};

// Eq. 18 at s = (1, 1, 1): the Hessian, hence the Lamé parameters, do not depend on alpha.
TEST_P(NonlinearEveryFamily, RestHessianAndLameParametersDoNotDependOnAlpha) {
  const auto base = family(GetParam());
  const Mat3 h0 = base->hess_stretch(Vec3::Ones());
  const Lame l0 = lame_from_energy(*base);
  for (double alpha : {0.5, 1.0, 2.0, 3.0}) {
    SCOPED_TRACE(testing::Message() << "alpha = " << alpha);
    const NonlinearMaterial wrapped(base, alpha);
    EXPECT_LE((wrapped.hess_stretch(Vec3::Ones()) - h0).norm(), 1e-12 * std::max(1.0, h0.norm()));
    const Lame l = lame_from_energy(wrapped);
    EXPECT_NEAR(l.lambda, l0.lambda, 1e-12 * std::max(1.0, std::abs(l0.lambda)));
    EXPECT_NEAR(l.mu, l0.mu, 1e-12 * std::max(1.0, std::abs(l0.mu)));
  }
}

TEST_P(NonlinearEveryFamily, WrapperAtAlphaOneHalfPassesTheBattery) {
  const auto& info = MaterialCatalog::instance().find(GetParam());
  const NonlinearMaterial wrapped(family(GetParam()), 0.5);
  test::check_material_battery(wrapped,
                               {.seed = 99u, .per_kind = 10, .rest_stable = info.rest_stable});
}

TEST_P(NonlinearEveryFamily, WrapperAtAlphaTwoPassesTheBattery) {
  const auto& info = MaterialCatalog::instance().find(GetParam());
  const NonlinearMaterial wrapped(family(GetParam()), 2.0);
  test::check_material_battery(wrapped,
                               {.seed = 42u, .per_kind = 10, .rest_stable = info.rest_stable});
}

TEST_P(NonlinearEveryFamily, AlphaOneIsTheBaseItself) {
  const auto base = family(GetParam());
  const NonlinearMaterial same(base, 1.0);
  EXPECT_EQ(same.domain(), base->domain());
  for (const auto& s : test::sample_set(5u, 3, base->domain() == Domain::All)) {
    EXPECT_EQ(same.psi(s.F), base->psi(s.F));
    EXPECT_EQ(same.pk1(s.F), base->pk1(s.F));
    EXPECT_EQ(same.evaluate(s.F).hessian, base->evaluate(s.F).hessian);
  }
}

INSTANTIATE_TEST_SUITE_P(Catalog, NonlinearEveryFamily, ::testing::ValuesIn(all_names()),
                         [](const auto& p) { return p.param; });

// Paper 002 §5: the Seth-Hill family is the nonlinearity exponent applied to linear
// corotational; alpha = 2 is StVK:
//   psi = mu/alpha^2 sum (s_i^alpha - 1)^2 + lambda/(2 alpha^2) (sum s_i^alpha - 3)^2.
TEST(Nonlinearity, LinearCorotationalBecomesSethHillAndStVK) {
  const double lambda = 3.7, mu = 1.3;
  const auto lc = std::make_shared<LinearCorotational>(lambda, mu);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.3, 2.5);
  for (double alpha : {0.5, 2.0, 3.0}) {
    const NonlinearMaterial seth_hill(lc, alpha);
    for (int n = 0; n < 20; ++n) {
      const Vec3 s(u(rng), u(rng), u(rng));
      const Vec3 sa = s.array().pow(alpha);
      const double tr = sa.sum() - 3.0;
      const double psi = mu / (alpha * alpha) * (sa.array() - 1.0).square().sum() +
                         lambda / (2.0 * alpha * alpha) * tr * tr;
      EXPECT_NEAR(seth_hill.psi_stretch(s), psi, 1e-12 * std::max(1.0, psi));
      if (alpha == 2.0) {  // StVK (paper 002 Table 1), written out in full
        const double stvk = mu / 4.0 * (s.array().square() - 1.0).square().sum() +
                            lambda / 8.0 * std::pow(s.squaredNorm() - 3.0, 2);
        EXPECT_NEAR(seth_hill.psi_stretch(s), stvk, 1e-12 * std::max(1.0, stvk));
        // dpsi/ds_i = mu (s_i^2 - 1) s_i + lambda/2 (|s|^2 - 3) s_i
        const Vec3 grad = (mu * (s.array().square() - 1.0) * s.array() +
                           0.5 * lambda * (s.squaredNorm() - 3.0) * s.array())
                              .matrix();
        EXPECT_LE((seth_hill.grad_stretch(s) - grad).norm(), 1e-12 * std::max(1.0, grad.norm()));
        // F view: StVK's P = F (2 mu E + lambda tr(E) I) with E = (F^T F - I)/2.
        const Mat3 F =
            test::random_rotation(rng) * s.asDiagonal() * test::random_rotation(rng).transpose();
        const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());
        const Mat3 P = F * (2.0 * mu * E + lambda * E.trace() * Mat3::Identity());
        EXPECT_LE((seth_hill.pk1(F) - P).norm(), 1e-11 * std::max(1.0, P.norm()));
      }
    }
  }
}

TEST(Nonlinearity, Eq17And18AgainstFiniteDifferencesOfEq16) {
  const auto lc = std::make_shared<LinearCorotational>(2.0, 0.7);
  const NonlinearMaterial m(lc, 2.5);
  const Vec3 s(0.8, 1.3, 1.7);
  const double h = 1e-5;
  for (int i = 0; i < 3; ++i) {
    Vec3 sp = s, sm = s;
    sp(i) += h;
    sm(i) -= h;
    EXPECT_NEAR(m.grad_stretch(s)(i), (m.psi_stretch(sp) - m.psi_stretch(sm)) / (2 * h), 1e-8);
    const Vec3 col = (m.grad_stretch(sp) - m.grad_stretch(sm)) / (2 * h);
    EXPECT_LE((m.hess_stretch(s).col(i) - col).norm(), 1e-7);
  }
}

TEST(Nonlinearity, PairEigenvaluesAreExactDividedDifferences) {
  const auto lc = std::make_shared<LinearCorotational>(2.0, 0.7);
  for (double alpha : {0.5, 2.0, 3.0}) {
    const NonlinearMaterial m(lc, alpha);
    for (double gap : {0.3, 1e-3, 1e-6, 1e-9, 0.0}) {
      const Vec3 s(1.4, 1.4 + gap, 0.6);
      const Vec3 p = m.grad_stretch(s);
      Vec3 twist, flip;
      m.pair_eigenvalues(s, p, m.hess_stretch(s), twist, flip);
      // Pair 2 couples (0, 1). Reference in long double from the closed form
      //   p_i = g(s_i) = (2 mu (x^alpha - 1) + lambda (T - 3)) x^alpha / (alpha x),
      // T = sum_i s_i^alpha held fixed (it is common to both stresses).
      const long double a = alpha, s0 = s(0), s1 = s(1), s2 = s(2);
      const long double T = std::pow(s0, a) + std::pow(s1, a) + std::pow(s2, a);
      auto g = [&](long double x) {
        return (2.0L * 0.7L * (std::pow(x, a) - 1.0L) + 2.0L * (T - 3.0L)) * std::pow(x, a) /
               (a * x);
      };
      long double ref;
      if (s1 - s0 > 1e-7L) {
        ref = (g(s1) - g(s0)) / (s1 - s0);
      } else {  // g' at the midpoint (error O(gap^2)):
                //   2 mu/alpha (2 alpha - 1) x^(2 alpha - 2) + (lambda (T - 3) - 2 mu)/alpha
                //   (alpha - 1) x^(alpha - 2)
        const long double x = 0.5L * (s0 + s1);
        ref = 2.0L * 0.7L / a * (2.0L * a - 1.0L) * std::pow(x, 2.0L * a - 2.0L) +
              (2.0L * (T - 3.0L) - 2.0L * 0.7L) / a * (a - 1.0L) * std::pow(x, a - 2.0L);
      }
      EXPECT_NEAR(flip(2), static_cast<double>(ref), 1e-12 * std::max(1.0, std::abs((double)ref)))
          << "alpha " << alpha << " gap " << gap;
      EXPECT_NEAR(twist(2), (p(0) + p(1)) / (s(0) + s(1)), 1e-13);
    }
  }
}

TEST(Nonlinearity, PowerDividedDifference) {
  for (double beta : {-1.5, 0.0, 0.5, 1.0, 2.0, 3.0}) {
    EXPECT_NEAR(power_divided_difference(2.0, 0.5, beta),
                (std::pow(2.0, beta) - std::pow(0.5, beta)) / 1.5, 1e-14);
    EXPECT_NEAR(power_divided_difference(1.3, 1.3, beta), beta * std::pow(1.3, beta - 1.0), 1e-15);
    // Near-equal arguments: the limit, to full accuracy (cancellation would lose ~7 digits).
    const double x = 1.3, y = 1.3 * (1.0 + 1e-9);
    const double mid = 0.5 * (x + y);
    EXPECT_NEAR(power_divided_difference(x, y, beta), beta * std::pow(mid, beta - 1.0), 1e-14);
  }
}

TEST(Nonlinearity, DomainAndValidation) {
  const auto lc = std::make_shared<LinearCorotational>(1.0, 1.0);
  EXPECT_EQ(NonlinearMaterial(lc, 1.0).domain(), Domain::All);
  const NonlinearMaterial m(lc, 2.0);
  EXPECT_EQ(m.domain(), Domain::PositiveJ);
  EXPECT_THROW(m.psi(Vec3(1.0, 1.0, -1.0).asDiagonal()), Error);
  for (double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    try {
      NonlinearMaterial(lc, bad);
      ADD_FAILURE() << "alpha = " << bad << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.context()).find("alpha"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(m.name(), "linear_corotational[alpha=2]");
}

// alpha > 1 stiffens and alpha < 1 softens under large stretch (paper 002 §5, Fig. 3).
TEST(Nonlinearity, StiffensAboveOneSoftensBelow) {
  const auto lc = std::make_shared<LinearCorotational>(0.0, 1.0);
  const Vec3 s(2.0, 1.0, 1.0);
  const double p1 = lc->grad_stretch(s)(0);
  EXPECT_GT(NonlinearMaterial(lc, 2.0).grad_stretch(s)(0), p1);
  EXPECT_LT(NonlinearMaterial(lc, 0.5).grad_stretch(s)(0), p1);
}

}  // namespace
}  // namespace sinew
