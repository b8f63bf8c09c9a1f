// Paper 000 §3.4: under uniform scaling F = s I (s < 0 is inverted), the stable Neo-Hookean energy
// (Eq. 14) has a spurious local minimum away from the rest shape s = 1 only when
// lambda/mu < 0.1525, i.e. nu <= -0.85. The threshold is in the model's own (lambda, mu), not in
// the Lamé parameters (lambda_Lame/mu_Lame = -0.63 there).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "sinew/material/catalog.hpp"

namespace sinew {
namespace {

struct Minimum {
  double s, psi;
};

std::unique_ptr<Material> snh(double ratio) {
  MaterialParameters p;
  p.values = {{"lambda", ratio}, {"mu", 1.0}};
  return MaterialCatalog::instance().make("stable_neo_hookean", p);
}

// d/ds Psi(s I) = P(s I) : I.
double slope(const Material& m, double s) { return m.pk1(s * Mat3::Identity()).trace(); }

// Local minima of psi(s I) on [lo, hi]: a dense scan for sign changes - to + of the slope, each
// refined by bisection. The grid is offset so no node lands on s = 0 or s = 1 exactly. The flat
// point s = 0 (slope ~ -3 lambda alpha s^2 <= 0 on both sides) is stationary but not a minimum,
// and the strict sign test skips it.
std::vector<Minimum> minima(const Material& m, double lo = -4.0, double hi = 4.0, int n = 80000) {
  std::vector<Minimum> out;
  const double h = (hi - lo) / n;
  double a = lo + 0.3819660112501051 * h;
  double da = slope(m, a);
  for (int k = 1; k < n; ++k) {
    const double b = a + h;
    const double db = slope(m, b);
    if (da < 0.0 && db > 0.0) {
      double l = a, r = b;
      for (int it = 0; it < 100 && r - l > 1e-15; ++it) {
        const double c = 0.5 * (l + r);
        (slope(m, c) < 0.0 ? l : r) = c;
      }
      const double s = 0.5 * (l + r);
      out.push_back({s, m.psi(s * Mat3::Identity())});
    }
    a = b;
    da = db;
  }
  return out;
}

void print(double ratio, const std::vector<Minimum>& found) {
  std::printf("lambda/mu = %.4f: %zu local minima along F = sI:", ratio, found.size());
  for (const auto& x : found) std::printf("  s = %.6f (psi = %.6f)", x.s, x.psi);
  std::printf("\n");
}

TEST(SnhSpuriousMinimum, PresentBelowThePapersThreshold) {
  const auto m = snh(0.15);
  const auto found = minima(*m);
  print(0.15, found);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_NEAR(found[1].s, 1.0, 1e-9);  // the rest shape
  // The spurious one: a deflated state between the flat point and the rest shape.
  EXPECT_GT(found[0].s, 0.1);
  EXPECT_LT(found[0].s, 0.9);
  // It is a genuine local minimum of psi, not only a root of the slope.
  const double s = found[0].s, d = 1e-3;
  EXPECT_LT(found[0].psi, m->psi((s - d) * Mat3::Identity()));
  EXPECT_LT(found[0].psi, m->psi((s + d) * Mat3::Identity()));
}

TEST(SnhSpuriousMinimum, AbsentAboveThePapersThreshold) {
  for (double ratio : {0.16, 0.625, 1.0, 10.0, 1000.0}) {  // 0.625: lambda_Lame = 0, nu = 0
    const auto found = minima(*snh(ratio));
    print(ratio, found);
    ASSERT_EQ(found.size(), 1u) << ratio;
    EXPECT_NEAR(found[0].s, 1.0, 1e-9) << ratio;
  }
}

TEST(SnhSpuriousMinimum, ThresholdIsThePapers) {
  // Bisection on lambda/mu between a ratio with and one without the spurious minimum.
  double with = 0.15, without = 0.16;
  for (int it = 0; it < 30; ++it) {
    const double mid = 0.5 * (with + without);
    (minima(*snh(mid), 0.05, 1.5, 20000).size() > 1 ? with : without) = mid;
  }
  const double ratio = 0.5 * (with + without);
  // nu in the model's parameters (§3.4): lambda_Lame = lambda - 5/8 mu, mu_Lame = 3/4 mu.
  const double lame_ratio = (ratio - 0.625) / 0.75;
  const double nu = (ratio - 0.625) / (2.0 * (ratio + 0.125));
  std::printf("spurious minimum disappears at lambda/mu = %.5f (paper: 0.1525); "
              "lambda_Lame/mu_Lame = %.4f, nu = %.4f (paper: nu <= -0.85)\n",
              ratio, lame_ratio, nu);
  EXPECT_NEAR(ratio, 0.1525, 5e-4);
  EXPECT_NEAR(nu, -0.85, 5e-3);
}

}  // namespace
}  // namespace sinew
