// Benchmarks with known answers at small sizes (docs/verification.md; the full tables are in
// tests/slow/verification_slow_test.cpp under the CTest label `slow`):
// * Cook's membrane, N = 2, 4, 8 trilinear hexahedra per edge, against the published Q1 tip
//   deflections of the reference computation (same energy, element and load);
// * a thick-walled plane-strain cylinder with its inner surface displaced radially, against the
//   1-D radial equilibrium solved by shooting (outer radius and inner pressure).
// Each test prints its numbers (run with --gtest_filter='VerificationBenchmark*').
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

#include "sinew/io/mesh_reader.hpp"
#include "sinew/material/derivative_check.hpp"
#include "sinew/material/spec.hpp"
#include "verification_benchmarks_support.hpp"

namespace sinew {
namespace {

using namespace verification;

// The test's own material must be right before it can verify anything.
TEST(VerificationBenchmark, SplitNeoHookeanDerivativesMatchDifferences) {
  const SplitNeoHookean m(kCookMu, cook_kappa());
  Mat3 F;
  F << 1.2, 0.1, -0.05, 0.03, 0.9, 0.15, -0.08, 0.02, 1.1;
  for (const Mat3& G : {F, Mat3(F * F), Mat3(Mat3::Identity() + 0.01 * F)}) {
    const auto check = check_material_derivatives(m, G);
    EXPECT_TRUE(check.passed(1e-6)) << "pk1 " << check.pk1_error << ", hessian " << check.hessian_error;
  }
  // Rest shape is stress free; its Lame parameters are (kappa - 2/3 mu, mu).
  EXPECT_LT(m.grad_stretch(Vec3::Ones()).norm(), 1e-14);
  const Mat3 h = m.hess_stretch(Vec3::Ones());
  EXPECT_NEAR(h(0, 0), cook_kappa() + 4.0 / 3.0 * kCookMu, 1e-12);  // lambda + 2 mu
  EXPECT_NEAR(h(0, 1), cook_kappa() - 2.0 / 3.0 * kCookMu, 1e-12);  // lambda
}

// The checked-in mesh of examples/verification/ is the one the benchmark solves.
TEST(VerificationBenchmark, CookMembraneMeshFileMatchesTheGenerator) {
  for (int N : {2, 16}) {
    const auto path = std::string(SINEW_EXAMPLES) + "/verification/cook_membrane_N" + std::to_string(N) + ".vtk";
    const VolumeMesh file = read_volume_mesh(path);
    const VolumeMesh made = cook_membrane_mesh(N);
    ASSERT_EQ(file.num_vertices(), made.num_vertices()) << path;
    ASSERT_EQ(file.num_elements(), made.num_elements()) << path;
    EXPECT_LT((file.vertices - made.vertices).cwiseAbs().maxCoeff(), 1e-9) << path;
    EXPECT_EQ(file.elements, made.elements) << path;
  }
}

// The reference's published Q1 values are those of the 1 mm slab with u_z free away from the
// clamp (its plane-strain faces are never tagged: the tag test reads the x coordinate); Sinew
// reproduces them so, and prints the plane-strain deflections beside them.
TEST(VerificationBenchmark, CookMembraneMatchesThePublishedQ1TableAtSmallSizes) {
  auto material = std::make_shared<SplitNeoHookean>(kCookMu, cook_kappa());
  std::printf("Cook's membrane (split Neo-Hookean, mu = 0.4225, nu = 0.3, F = 1 N)\n");
  std::printf("%4s %14s %12s %10s %8s %18s\n", "N", "u_z free (mm)", "ref Q1 (mm)", "diff", "Newton", "plane strain (mm)");
  // u_z free does not converge at N = 8 (the 1 mm slab leaves the plane: Newton on the projected
  // Hessian finds an out-of-plane path that the reference's symmetric solve never sees).
  for (int N : {2, 4}) {
    const CookResult r = solve_cook_membrane(N, material, kCookMu, false);
    ASSERT_TRUE(r.converged) << "N = " << N << ": " << r.failure;
    const CookResult ps = solve_cook_membrane(N, material, kCookMu, true);
    ASSERT_TRUE(ps.converged) << "N = " << N << " (plane strain): " << ps.failure;
    const double ref = cook_reference_q1(N);
    std::printf("%4d %14.4f %12.2f %10.4f %8d %18.4f\n", N, r.tip, ref, r.tip - ref, r.iterations, ps.tip);
    // The reference prints two decimals: agreement to its rounding (plus a little).
    EXPECT_NEAR(r.tip, ref, 0.006) << "N = " << N;
    EXPECT_LT(ps.tip, r.tip) << "plane strain is stiffer";
  }
}

TEST(VerificationBenchmark, ThickCylinderMatchesTheRadialSolution) {
  const double A = 1.0, B = 2.0, a = 1.3;
  MaterialSpec spec;
  spec.family = "neo_hookean";
  spec.target = YoungPoisson{1000.0, 0.3};
  const auto built = build_material_detailed(spec);
  const double mu = built.parameters.values.at("mu"), lambda = built.parameters.values.at("lambda");
  const RadialSolution exact = cylinder_radial_solution(A, B, a, mu, lambda);
  std::printf("Thick cylinder (neo_hookean, E = 1000, nu = 0.3, A = 1, B = 2, inner radius -> 1.3)\n");
  std::printf("ODE: outer radius %.8f, inner P_R %.8f\n", exact.outer_radius, exact.inner_PR);
  double previous_u = 0.0, previous_p = 0.0;
  for (int Nr : {2, 4}) {
    const int Nt = 8 * Nr, steps = 6;
    const CylinderResult r = solve_cylinder(A, B, a, built.material, mu, Nr, Nt, steps);
    ASSERT_TRUE(r.converged) << "Nr = " << Nr << ": " << r.failure;
    const double thickness = (B - A) / Nr;
    const double force_exact = -exact.inner_PR * 2.0 * std::numbers::pi * A * thickness;
    const double err_u = std::abs(r.outer_radius - exact.outer_radius) / (exact.outer_radius - B);
    const double err_p = std::abs(r.inner_force - force_exact) / force_exact;
    std::printf("Nr %2d Nt %3d: outer radius %.8f (rel. error of u %.2e), inner force %.6e vs %.6e (rel. %.2e)\n",
                Nr, Nt, r.outer_radius, err_u, r.inner_force, force_exact, err_p);
    if (Nr == 4) {
      EXPECT_LT(err_u, 3e-3);
      EXPECT_LT(err_p, 5e-3);
      // Second-order convergence: halving h divides the error by about 4.
      EXPECT_LT(err_u, 0.4 * previous_u);
      EXPECT_LT(err_p, 0.4 * previous_p);
    }
    previous_u = err_u;
    previous_p = err_p;
  }
}

}  // namespace
}  // namespace sinew
