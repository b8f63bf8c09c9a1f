// Stress-stretch curves: lateral stretch solve and the small-strain limit (E, nu) of every family.
#include <gtest/gtest.h>

#include <cmath>

#include "sinew/core/error.hpp"
#include "sinew/material/catalog.hpp"
#include "sinew/material/families/corotational.hpp"
#include "sinew/material/curve.hpp"
#include "sinew/material/lame.hpp"
#include "sinew/material/nonlinearity.hpp"
#include "sinew/material/normalization.hpp"

namespace sinew {
namespace {

// Linear corotational in uniaxial tension is exactly linear: t = 1 - nu (s - 1) and
// P00 = E (s - 1) while t > 0.
TEST(Curve, LinearCorotationalUniaxialIsExactlyLinear) {
  const double lambda = 4.0, mu = 1.5;
  const LinearCorotational m(lambda, mu);
  const YoungPoisson ev = young_poisson({lambda, mu});
  const auto curve = stress_stretch_curve(m, CurveMode::Uniaxial, 0.5, 1.8, 13);
  ASSERT_EQ(curve.size(), 14u);
  EXPECT_EQ(curve.front().stretch, 0.5);
  EXPECT_EQ(curve.back().stretch, 1.8);
  for (const auto& p : curve) {
    EXPECT_NEAR(p.lateral, 1.0 - ev.nu * (p.stretch - 1.0), 1e-13);
    EXPECT_NEAR(p.stress, ev.E * (p.stretch - 1.0), 1e-12);
    EXPECT_NEAR(p.J, p.stretch * p.lateral * p.lateral, 1e-14);
    EXPECT_NEAR(p.psi, m.psi(curve_deformation(CurveMode::Uniaxial, p.stretch, p.lateral)), 1e-14);
  }
}

TEST(Curve, LinearCorotationalBiaxialAndShear) {
  const double lambda = 4.0, mu = 1.5;
  const LinearCorotational m(lambda, mu);
  for (const auto& p : stress_stretch_curve(m, CurveMode::Biaxial, 0.8, 1.2, 4)) {
    // P22 = 2 mu (t - 1) + lambda (2 s + t - 3) = 0
    EXPECT_NEAR(p.lateral - 1.0, -2.0 * lambda * (p.stretch - 1.0) / (2.0 * mu + lambda), 1e-13);
  }
  const auto shear = stress_stretch_curve(m, CurveMode::Shear, -1e-6, 1e-6, 2);
  EXPECT_EQ(shear[1].lateral, 1.0);
  EXPECT_NEAR(shear[2].stress / 1e-6, mu, 1e-6);  // small shear: P01 = mu_L gamma
  EXPECT_NEAR(shear[0].stress / -1e-6, mu, 1e-6);
}

// Theorem 3.1 seen from outside: at small strain every rest-stable family, normalised to
// (E, nu), stretches with stress E (s - 1) and lateral contraction nu (s - 1).
TEST(Curve, EveryFamilyHasItsYoungsModulusAndPoissonsRatioAtSmallStrain) {
  for (const auto& info : MaterialCatalog::instance().all()) {
    SCOPED_TRACE(info.name);
    if (!info.rest_stable) continue;
    MaterialParameters params = MaterialCatalog::instance().complete(info.name, {});
    if (info.normalized.size() == 2) params = normalize(info, {}, YoungPoisson{2.0, 0.3});
    if (info.normalized.size() == 1) params = normalize(info, {}, YoungPoisson{2.0, 0.0});
    const auto base = info.make(params);
    const Lame lame = lame_from_energy(*base);
    if (!(lame.lambda + lame.mu > 0.0) || !(lame.mu > 0.0)) continue;
    const YoungPoisson ev = young_poisson(lame);
    for (double alpha : {1.0, 2.0}) {
      const NonlinearMaterial m(std::shared_ptr<const Material>(info.make(params)), alpha);
      for (double strain : {1e-5, -1e-5}) {
        const double s = 1.0 + strain;
        const double t = solve_lateral_stretch(m, CurveMode::Uniaxial, s);
        const double stress = m.pk1(curve_deformation(CurveMode::Uniaxial, s, t))(0, 0);
        EXPECT_NEAR(stress / strain, ev.E, 1e-3 * ev.E) << "alpha " << alpha;
        EXPECT_NEAR((1.0 - t) / strain, ev.nu, 1e-3) << "alpha " << alpha;
      }
    }
  }
}

TEST(Curve, ValidatesItsArguments) {
  const LinearCorotational m(1.0, 1.0);
  auto context_of = [&](CurveMode mode, double from, double to, int steps) -> std::string {
    try {
      stress_stretch_curve(m, mode, from, to, steps);
    } catch (const Error& e) {
      return e.context();
    }
    return "(no error)";
  };
  EXPECT_EQ(context_of(CurveMode::Uniaxial, 2.0, 1.0, 5), "stretch-from");
  EXPECT_EQ(context_of(CurveMode::Uniaxial, 1.0, 1.0, 5), "stretch-from");
  EXPECT_EQ(context_of(CurveMode::Uniaxial, 0.0, 1.0, 5), "stretch-from");
  EXPECT_EQ(context_of(CurveMode::Uniaxial, std::nan(""), 1.0, 5), "stretch-from");
  EXPECT_EQ(context_of(CurveMode::Uniaxial, 0.5, INFINITY, 5), "stretch-to");
  EXPECT_EQ(context_of(CurveMode::Uniaxial, 0.5, 1.5, 0), "steps");
  EXPECT_EQ(context_of(CurveMode::Shear, -1.0, 1.0, 4), "(no error)");
  EXPECT_THROW(parse_curve_mode("torsion"), Error);
  // Corotational volume term: past s = 3 + 2 mu / lambda no t > 0 frees the lateral faces.
  EXPECT_THROW(solve_lateral_stretch(m, CurveMode::Uniaxial, 6.0), Error);
}

}  // namespace
}  // namespace sinew
