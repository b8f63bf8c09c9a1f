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
#include "io_test_support.hpp"
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
// clamp (its plane-strain faces are never tagged: the tag test reads the x coordinate), on the
// symmetric solution its Newton iterates keep. Sinew's half model of that slab (mid-plane
// symmetry, tests/verification_benchmarks_support.hpp) reproduces it to its two printed decimals;
// the plane-strain deflections (the setup; stiffer) are printed beside them.
TEST(VerificationBenchmark, CookMembraneMatchesThePublishedQ1TableAtSmallSizes) {
  auto material = std::make_shared<SplitNeoHookean>(kCookMu, cook_kappa());
  std::printf("Cook's membrane (split Neo-Hookean, mu = 0.4225, nu = 0.3, F = 1 N)\n");
  std::printf("%4s %16s %12s %10s %8s %18s\n", "N", "symmetric slab", "ref Q1 (mm)", "diff", "Newton", "plane strain (mm)");
  for (int N : {2, 4, 8}) {
    const CookResult r = solve_cook_membrane(N, material, kCookMu, CookThickness::HalfSlab);
    ASSERT_TRUE(r.converged) << "N = " << N << ": " << r.failure;
    const CookResult ps = solve_cook_membrane(N, material, kCookMu, CookThickness::PlaneStrain);
    ASSERT_TRUE(ps.converged) << "N = " << N << " (plane strain): " << ps.failure;
    const double ref = cook_reference_q1(N);
    std::printf("%4d %16.4f %12.2f %10.4f %8d %18.4f\n", N, r.tip, ref, r.tip - ref, r.iterations, ps.tip);
    // The reference prints two decimals: agreement to its rounding.
    EXPECT_NEAR(r.tip, ref, 0.005) << "N = " << N;
    EXPECT_LT(ps.tip, r.tip) << "plane strain is stiffer";
  }
  // The full slab with u_z free is the same problem at N = 2, 4 (its symmetric solution is found).
  for (int N : {2, 4}) {
    const CookResult r = solve_cook_membrane(N, material, kCookMu, CookThickness::FreeSlab);
    ASSERT_TRUE(r.converged) << "N = " << N << ": " << r.failure;
    EXPECT_NEAR(r.tip, solve_cook_membrane(N, material, kCookMu, CookThickness::HalfSlab).tip, 1e-3) << "N = " << N;
  }
}

TEST(VerificationBenchmark, ThickCylinderMatchesTheRadialSolution) {
  const double A = 1.0, B = 2.0, a = 1.3;
  const CylinderMaterial built = cylinder_material();
  const double mu = built.mu, lambda = built.lambda;
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

// The pressure-loaded cylinder through its scene (examples/verification/thick_cylinder.json):
// inner and outer radii against the radial ODE with the follower-pressure condition, and the
// symmetry roller's reaction against the hoop force p a h that balances the pressure on the quarter.
TEST(VerificationBenchmark, ThickCylinderUnderInternalPressureMatchesTheRadialSolution) {
  test::TempDir dir;
  double previous_a = 0.0, previous_b = 0.0;
  std::printf("Thick cylinder under internal pressure (scene, quarter model, neo_hookean E = 1000, nu = 0.3, p = 100)\n");
  for (int Nr : {2, 4}) {
    const PressureCylinderRun r = run_pressure_cylinder(Nr, dir.path());
    ASSERT_TRUE(r.converged) << "Nr = " << Nr << ": " << r.failure;
    const PressureSolution exact = cylinder_pressure_solution(1.0, 2.0, r.pressure, r.mu, r.lambda);
    const double err_a = std::abs(r.inner_radius - exact.inner_radius) / (exact.inner_radius - 1.0);
    const double err_b = std::abs(r.outer_radius - exact.outer_radius) / (exact.outer_radius - 2.0);
    const double hoop = -r.pressure * exact.inner_radius * r.thickness;
    const double err_f = std::abs(r.symmetry_reaction - hoop) / std::abs(hoop);
    std::printf("Nr %2d: inner radius %.8f (ODE %.8f, rel. error of u %.2e), outer %.8f (ODE %.8f, %.2e), "
                "roller reaction %.6e vs -p a h %.6e (%.2e)\n",
                Nr, r.inner_radius, exact.inner_radius, err_a, r.outer_radius, exact.outer_radius, err_b,
                r.symmetry_reaction, hoop, err_f);
    if (Nr == 4) {
      EXPECT_LT(err_a, 2e-2);
      EXPECT_LT(err_b, 2e-2);
      EXPECT_LT(err_f, 1e-2);
      EXPECT_LT(err_a, 0.4 * previous_a) << "second order";
      EXPECT_LT(err_b, 0.4 * previous_b) << "second order";
    }
    previous_a = err_a;
    previous_b = err_b;
  }
}

// The Cook's membrane scene (examples/verification/cook_membrane.json: clamp, plane strain as
// z-rollers, a ramped traction, the catalog's neo_hookean) gives the C++ benchmark's tip deflection.
TEST(VerificationBenchmark, CookMembraneSceneMatchesTheBenchmarkSolve) {
  const Scene scene = load_scene(std::filesystem::path(SINEW_EXAMPLES) / "verification" / "cook_membrane.json");
  const RunSummary summary = run_scene(scene, RunOptions{});
  ASSERT_TRUE(summary.all_converged());
  const VolumeMesh rest = build_scene_mesh(scene);
  double tip = 0.0;
  int count = 0;
  for (Eigen::Index v = 0; v < rest.num_vertices(); ++v)
    if (std::abs(rest.vertices(v, 0) - 48.0) < 1e-9 && std::abs(rest.vertices(v, 1) - 60.0) < 1e-9) {
      tip += summary.x(3 * v + 1) - rest.vertices(v, 1);
      ++count;
    }
  ASSERT_EQ(count, 2);
  tip /= count;
  const auto material = build_material_detailed(scene.material).material;
  const CookResult api = solve_cook_membrane(16, material, kCookMu, CookThickness::PlaneStrain);
  ASSERT_TRUE(api.converged) << api.failure;
  std::printf("Cook's membrane scene (N = 16, neo_hookean, plane strain): tip %.6f mm, C++ solve %.6f mm\n", tip, api.tip);
  EXPECT_NEAR(tip, api.tip, 1e-6 * api.tip);
}

}  // namespace
}  // namespace sinew
