// The backtracking Armijo line search on its own: the full step when it decreases enough,
// halving otherwise, steps outside the energy's domain skipped, the near-convergence rule that
// accepts a lower residual when energy differences drown in rounding, and failure.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sinew/solver/line_search.hpp"

namespace sinew {
namespace {

// E(y) = 1/2 y^T D y with D = diag(1, 10).
struct Quadratic {
  Eigen::Vector2d D{1.0, 10.0};
  int values = 0, gradients = 0;
  LineSearchObjective objective() {
    return {[this](const Eigen::VectorXd& y) {
              ++values;
              return 0.5 * y.dot(D.asDiagonal() * y);
            },
            [this](const Eigen::VectorXd& y) {
              ++gradients;
              return Eigen::VectorXd(D.asDiagonal() * y);
            }};
  }
};

struct Start {
  Eigen::VectorXd x, g;
  double energy, residual;
};
Start start(Quadratic& q, const Eigen::Vector2d& x) {
  return {x, q.D.asDiagonal() * x, 0.5 * x.dot(q.D.asDiagonal() * x), (q.D.asDiagonal() * x).norm()};
}

TEST(LineSearch, TakesTheFullNewtonStep) {
  Quadratic q;
  const Start s = start(q, {1.0, 1.0});
  const Eigen::VectorXd d = -s.g.cwiseQuotient(q.D);  // the Newton step lands on the minimum
  Eigen::VectorXd trial;
  const LineSearchResult r =
      backtracking_line_search(q.objective(), s.x, d, s.energy, s.g.dot(d), s.residual, {}, trial);
  EXPECT_TRUE(r.accepted);
  EXPECT_EQ(r.step, 1.0);
  EXPECT_EQ(r.evaluations, 1);
  EXPECT_NEAR(r.energy, 0.0, 1e-15);
  EXPECT_LE(trial.norm(), 1e-15);
  EXPECT_EQ(q.gradients, 0);
}

TEST(LineSearch, HalvesAnOverlongStepUntilArmijoHolds) {
  Quadratic q;
  const Start s = start(q, {1.0, 1.0});
  const Eigen::VectorXd d = -8.0 * s.g.cwiseQuotient(q.D);  // 8x too long: step 1/8 is exact
  Eigen::VectorXd trial;
  LineSearchSettings settings;
  const LineSearchResult r =
      backtracking_line_search(q.objective(), s.x, d, s.energy, s.g.dot(d), s.residual, settings, trial);
  ASSERT_TRUE(r.accepted);
  // E(x + a d) = E(x) (1 - 8a)^2 first satisfies Armijo (c = 1e-4) at a = 1/8 (1/4 gives E(x)).
  EXPECT_EQ(r.step, 0.125);
  EXPECT_EQ(r.evaluations, 4);
  EXPECT_EQ(q.values, 4);
  EXPECT_TRUE(trial.isApprox(s.x + 0.125 * d));
  // The Armijo constant decides: along d3, E(x + a d3) = E(x) (1 - 3a)^2 and g.d3 = -6 E(x).
  const Eigen::VectorXd d3 = -3.0 * s.g.cwiseQuotient(q.D);
  EXPECT_EQ(backtracking_line_search(q.objective(), s.x, d3, s.energy, s.g.dot(d3), s.residual, settings, trial).step, 0.5);
  settings.armijo = 0.5;  // needs (1 - 3a)^2 <= 1 - 3a: a <= 1/3
  EXPECT_EQ(backtracking_line_search(q.objective(), s.x, d3, s.energy, s.g.dot(d3), s.residual, settings, trial).step, 0.25);
  settings.armijo = 0.9;  // needs (1 - 3a)^2 <= 1 - 5.4a: a <= 1/15
  EXPECT_EQ(backtracking_line_search(q.objective(), s.x, d3, s.energy, s.g.dot(d3), s.residual, settings, trial).step, 0.0625);
}

TEST(LineSearch, SkipsStepsOutsideTheDomain) {
  Quadratic q;
  const Start s = start(q, {1.0, 1.0});
  const Eigen::VectorXd d = -s.g.cwiseQuotient(q.D);
  LineSearchObjective o = q.objective();
  auto inner = o.value;
  o.value = [&](const Eigen::VectorXd& y) {  // the domain is y(0) > 0.2: steps a >= 0.8 leave it
    return y(0) > 0.2 ? inner(y) : std::numeric_limits<double>::infinity();
  };
  Eigen::VectorXd trial;
  const LineSearchResult r = backtracking_line_search(o, s.x, d, s.energy, s.g.dot(d), s.residual, {}, trial);
  ASSERT_TRUE(r.accepted);
  EXPECT_EQ(r.step, 0.5);
  EXPECT_EQ(r.evaluations, 2);
  EXPECT_TRUE(std::isfinite(r.energy));
}

TEST(LineSearch, AcceptsALowerResidualWhenTheEnergyDifferenceIsRounding) {
  // A flat energy (all differences below 1e-12 relative) whose gradient still points somewhere.
  const double level = 1e6;
  LineSearchObjective o{[&](const Eigen::VectorXd& y) { return level + 1e-8 * y.squaredNorm(); },
                        [](const Eigen::VectorXd& y) { return Eigen::VectorXd(2e-8 * y); }};
  const Eigen::VectorXd x = Eigen::Vector2d(1.0, 0.0);
  const Eigen::VectorXd g = 2e-8 * x;
  // A step that overshoots to -1.5 x raises E by 1.25e-8 (no Armijo) and the gradient norm too;
  // half of it lands at 0.25 x, lower energy, lower gradient.
  const Eigen::VectorXd d = -2.5 * x;
  const double energy = level + 1e-8;
  Eigen::VectorXd trial;
  LineSearchSettings settings;
  settings.armijo = 1.0;  // Armijo needs a decrease of |a slope| = 5e-8 a, more than achieved
  const LineSearchResult r = backtracking_line_search(o, x, d, energy, g.dot(d), g.norm(), settings, trial);
  ASSERT_TRUE(r.accepted);
  EXPECT_EQ(r.step, 0.5);
  EXPECT_TRUE(trial.isApprox(Eigen::Vector2d(-0.25, 0.0)));
}

TEST(LineSearch, FailsAlongAnAscentDirection) {
  Quadratic q;
  const Start s = start(q, {1.0, 1.0});
  Eigen::VectorXd trial;
  LineSearchSettings settings;
  settings.max_steps = 5;
  const LineSearchResult r =
      backtracking_line_search(q.objective(), s.x, s.g, s.energy, -s.g.squaredNorm(), s.residual, settings, trial);
  EXPECT_FALSE(r.accepted);
  EXPECT_EQ(r.evaluations, 5);
  EXPECT_EQ(r.step, 1.0 / 16.0);
}

}  // namespace
}  // namespace sinew
