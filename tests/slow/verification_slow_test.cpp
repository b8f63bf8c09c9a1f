// The verification benchmarks at full size (docs/verification.md): Cook's membrane for
// N = 2 ... 64 elements per edge against the published Q1 table and converged value, and the
// thick-walled cylinder's mesh convergence against the radial solution. The small sizes run in
// the default suite (tests/verification_benchmarks_test.cpp). Skips itself unless
// SINEW_SLOW_TESTS=1:
//   SINEW_SLOW_TESTS=1 build/tests/sinew_slow_tests --gtest_filter='VerificationSlow*'
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>
#include <cstdlib>
#include <string>
#include <vector>

#include "../verification_benchmarks_support.hpp"
#include "sinew/material/spec.hpp"

namespace sinew {
namespace {

using namespace verification;

bool slow_enabled() {
  const char* v = std::getenv("SINEW_SLOW_TESTS");
  return v && std::string(v) == "1";
}

// Plane strain (u_z = 0 everywhere), N = 2 ... 64: the published table is of the slab with u_z
// free (tests/verification_benchmarks_test.cpp compares it at N = 2, 4), so this prints the
// plane-strain convergence of the reference's energy and of the catalog's neo_hookean and asserts
// monotone convergence with shrinking increments.
TEST(VerificationSlow, CookMembraneConvergenceTable) {
  if (!slow_enabled()) GTEST_SKIP() << "set SINEW_SLOW_TESTS=1";
  auto split = std::make_shared<SplitNeoHookean>(kCookMu, cook_kappa());
  MaterialSpec spec;
  spec.family = "neo_hookean";
  spec.parameters.values["mu"] = kCookMu;
  spec.parameters.values["lambda"] = cook_kappa() - 2.0 / 3.0 * kCookMu;
  const auto standard = build_material_detailed(spec).material;
  std::printf("%4s %22s %22s\n", "N", "split NH, plane strain", "neo_hookean, plane str.");
  std::vector<double> tips;
  for (int N : {2, 4, 8, 16, 32, 64}) {
    const CookResult r = solve_cook_membrane(N, split, kCookMu);
    ASSERT_TRUE(r.converged) << "N = " << N << ": " << r.failure;
    const CookResult s = solve_cook_membrane(N, standard, kCookMu);
    ASSERT_TRUE(s.converged) << "N = " << N << " (neo_hookean): " << s.failure;
    std::printf("%4d %22.4f %22.4f\n", N, r.tip, s.tip);
    std::fflush(stdout);
    tips.push_back(r.tip);
  }
  for (size_t i = 1; i < tips.size(); ++i) EXPECT_GT(tips[i], tips[i - 1]) << "trilinear hexahedra converge from below";
  for (size_t i = 2; i < tips.size(); ++i) EXPECT_LT(tips[i] - tips[i - 1], 0.5 * (tips[i - 1] - tips[i - 2]));
}

TEST(VerificationSlow, ThickCylinderConvergence) {
  if (!slow_enabled()) GTEST_SKIP() << "set SINEW_SLOW_TESTS=1";
  const double A = 1.0, B = 2.0, a = 1.3;
  MaterialSpec spec;
  spec.family = "neo_hookean";
  spec.target = YoungPoisson{1000.0, 0.3};
  const auto built = build_material_detailed(spec);
  const double mu = built.parameters.values.at("mu"), lambda = built.parameters.values.at("lambda");
  const RadialSolution exact = cylinder_radial_solution(A, B, a, mu, lambda);
  std::printf("ODE: outer radius %.10f, inner P_R %.10f\n", exact.outer_radius, exact.inner_PR);
  double previous_u = 0.0, previous_p = 0.0;
  for (int Nr : {2, 4, 8, 16}) {  // Nr = 32 (8192 hexahedra) threw in the solver: not yet investigated
    const int Nt = 8 * Nr;
    const CylinderResult r = solve_cylinder(A, B, a, built.material, mu, Nr, Nt, 6);
    ASSERT_TRUE(r.converged) << "Nr = " << Nr << ": " << r.failure;
    const double force_exact = -exact.inner_PR * 2.0 * std::numbers::pi * A * (B - A) / Nr;
    const double err_u = std::abs(r.outer_radius - exact.outer_radius) / (exact.outer_radius - B);
    const double err_p = std::abs(r.inner_force - force_exact) / force_exact;
    std::printf("Nr %2d Nt %3d: rel. error outer displacement %.3e, inner force %.3e\n", Nr, Nt, err_u, err_p);
    std::fflush(stdout);
    if (Nr > 2) {
      EXPECT_LT(err_u, 0.4 * previous_u) << "Nr = " << Nr;
      EXPECT_LT(err_p, 0.4 * previous_p) << "Nr = " << Nr;
    }
    previous_u = err_u;
    previous_p = err_p;
  }
  EXPECT_LT(previous_u, 2e-4);
  EXPECT_LT(previous_p, 3e-4);
}

}  // namespace
}  // namespace sinew
