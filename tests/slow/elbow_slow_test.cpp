// Paper 000 Fig. 2 / Fig. 10 at a finer resolution: elbow flexion 0 -> 120 degrees on the shipped
// arm surface. For nu in {0.3, 0.4, 0.45, 0.488} SNH's bulge and volume change; self-contact
// holding the closed crease at nu = 0.488 (no sample deeper than a quarter cell, biceps and
// forearm within half a cell; nu = 0.45 printed beside it); at nu = 0.488 SNH against co-rotational and StVK + Kikuuwe
// (volume change, bulges, contact, interpenetration), with per-frame Newton/CG iterations and
// time beside the paper's averages (13.7 Newton, 5,860 CG, 25.6 s per step on 45,809
// hexahedra). Skips itself unless SINEW_SLOW_TESTS=1:
//   SINEW_SLOW_TESTS=1 build/tests/sinew_slow_tests --gtest_filter='ElbowSlow*'
// SINEW_ELBOW_CELL (metres, default 0.01), SINEW_ELBOW_FRAMES (default 12),
// SINEW_ELBOW_SUBSTEPS (flexion increments per frame for the contact runs, default 1),
// SINEW_ELBOW_COMPARE_CELL (the model comparison's cell, default 0.02),
// SINEW_ELBOW_SURFACE (the arm surface to voxelise, default examples/meshes/arm.obj; "analytic"
// for the occupancy lattice of arm_sdf()). One TBB thread unless SINEW_ELBOW_THREADS says more.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <tbb/global_control.h>

#include "experiments/elbow_experiment.hpp"

namespace sinew {
namespace {

bool slow_enabled() {
  const char* v = std::getenv("SINEW_SLOW_TESTS");
  return v && std::string(v) == "1";
}

double env_number(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v ? std::atof(v) : fallback;
}

struct RunSettings {
  double cell = env_number("SINEW_ELBOW_CELL", 0.01);
  bool contact = false;
  int substeps = 1;
};

ElbowRun run(const std::string& family, double nu, const RunSettings& s) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                              static_cast<size_t>(env_number("SINEW_ELBOW_THREADS", 1)));
  ElbowConfig c;
  const char* surface = std::getenv("SINEW_ELBOW_SURFACE");
  if (!surface) c.arm_surface = std::filesystem::path(SINEW_EXAMPLES) / "meshes" / "arm.obj";
  else if (std::string(surface) != "analytic") c.arm_surface = surface;
  c.family = family;
  c.nu = nu;
  if (family == "stvk_kikuuwe") c.parameters["kappa"] = 8e8;  // Fig. 10's compression resistance
  c.cell_size = s.cell;
  c.bone_radius = std::max(0.016, 1.05 * c.cell_size);
  c.frames = static_cast<int>(env_number("SINEW_ELBOW_FRAMES", 12));
  c.substeps = s.substeps;
  c.self_contact = s.contact;
  c.solver = paper_solver(1e-3, 300);
  c.solver.linear.kind = "cholmod";  // a few thousand hexahedra: direct solves are fastest here
  const ElbowRun r = run_elbow(c, [&](const ElbowFrame& f) {
    std::printf("  %s nu %.3f frame %2d: %s, %3d Newton, %6d linear, %.1f s, volume %+.2f %%, bulge %.2f / %.2f mm, "
                "%d penetrating samples (max %.2f mm), gap %.2f mm%s%s\n",
                family.c_str(), nu, f.solve.frame, f.solve.converged ? "converged" : "NOT converged", f.solve.newton_iterations,
                f.solve.linear_iterations, f.solve.seconds, f.volume_change_percent, 1e3 * f.biceps_bulge, 1e3 * f.forearm_bulge,
                f.contacts, 1e3 * f.max_depth, 1e3 * f.gap, f.solve.failure.empty() ? "" : ": ", f.solve.failure.c_str());
    std::fflush(stdout);
  });
  std::printf("elbow %s nu %.3f, %ld hexahedra (paper %ld), contact %s, %d increments/frame: biceps bulge %.2f mm, forearm "
              "bulge %.2f mm, volume %+.2f %%, gap %.2f mm, deepest %.2f mm, in contact: %s, interpenetrating: %s; per frame "
              "%.1f Newton, %.0f linear, %.1f s",
              family.c_str(), nu, static_cast<long>(r.elements), kPaperElbowHexes, c.self_contact ? "on" : "off", c.substeps,
              1e3 * r.biceps_bulge(), 1e3 * r.forearm_bulge(), r.volume_change_percent(), 1e3 * r.frames.back().gap,
              1e3 * r.frames.back().max_depth, r.in_contact() ? "yes" : "no", r.interpenetrating() ? "yes" : "no", r.mean_newton(),
              r.mean_linear(), r.mean_seconds());
  for (const auto& p : kPaperElbow)
    if (family == p.family) std::printf(" (paper: %.1f Newton, %.0f CG, %.1f s)", p.newton, p.cg, p.seconds);
  std::printf("\n");
  return r;
}

TEST(ElbowSlow, BulgeGrowsAndVolumeLossShrinksWithPoissonRatio) {
  if (!slow_enabled()) GTEST_SKIP() << "set SINEW_SLOW_TESTS=1 to run it";
  double previous_biceps = -1.0, previous_forearm = -1.0, previous_loss = 1e9;
  for (double nu : {0.3, 0.4, 0.45, 0.488}) {
    const ElbowRun r = run("stable_neo_hookean", nu, RunSettings{});
    EXPECT_TRUE(r.all_converged()) << nu;
    EXPECT_GT(r.biceps_bulge(), previous_biceps) << nu;
    EXPECT_GT(r.forearm_bulge(), previous_forearm) << nu;
    EXPECT_LT(-r.volume_change_percent(), previous_loss) << nu;
    previous_biceps = r.biceps_bulge();
    previous_forearm = r.forearm_bulge();
    previous_loss = -r.volume_change_percent();
  }
}

// The crease closes at about 100 degrees; biceps and forearm end touching, no sample deeper than a
// quarter cell, at Fig. 10's nu = 0.488 and at nu = 0.45.
TEST(ElbowSlow, SelfContactHoldsTheClosedCrease) {
  if (!slow_enabled()) GTEST_SKIP() << "set SINEW_SLOW_TESTS=1 to run it";
  RunSettings s;
  s.contact = true;
  s.substeps = static_cast<int>(env_number("SINEW_ELBOW_SUBSTEPS", 1));
  const ElbowRun r = run("stable_neo_hookean", 0.488, s);  // the and Fig. 10's value
  EXPECT_TRUE(r.all_converged());
  EXPECT_TRUE(r.in_contact());
  EXPECT_FALSE(r.interpenetrating());
  // The more compressible crease folds sharply at the joint plane. With contacts added only at
  // converged states its samples ended 15-30 mm deep and the last frame did not converge; with
  // shallow samples also added at accepted Newton steps it holds (docs/experiments.md).
  const ElbowRun compressible = run("stable_neo_hookean", 0.45, s);
  EXPECT_TRUE(compressible.all_converged());
  EXPECT_TRUE(compressible.in_contact());
  EXPECT_FALSE(compressible.interpenetrating());
}

// Fig. 10's comparison at nu = 0.488, contact on, at a coarse cell so that all three finish.
// Every run is reported, converged or not; the assertions are the paper's qualitative claims
// that hold here: SNH keeps the volume better than co-rotational and stays in contact.
TEST(ElbowSlow, ModelComparisonAtNu0488) {
  if (!slow_enabled()) GTEST_SKIP() << "set SINEW_SLOW_TESTS=1 to run it";
  RunSettings s;
  s.cell = env_number("SINEW_ELBOW_COMPARE_CELL", 0.02);
  s.contact = true;
  s.substeps = static_cast<int>(env_number("SINEW_ELBOW_SUBSTEPS", 1));
  const ElbowRun snh = run("stable_neo_hookean", 0.488, s);
  const ElbowRun corot = run("corotational", 0.488, s);
  const ElbowRun stvk = run("stvk_kikuuwe", 0.488, s);
  EXPECT_LT(std::abs(snh.volume_change_percent()), std::abs(corot.volume_change_percent()));
  EXPECT_TRUE(snh.in_contact());
  EXPECT_FALSE(stvk.frames.empty());
}

}  // namespace
}  // namespace sinew
