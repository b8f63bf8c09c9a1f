// Paper 000 §6 at full size: the stretch test on 306,327 hexahedra (the paper's 306,406; 24
// frames to 3.4x) for the four models of Fig. 5-6, and the scramble test on an 8^3 cube. These
// take hours on a small machine, so they carry the CTest label `slow` and skip themselves unless
// SINEW_SLOW_TESTS=1:
//   SINEW_SLOW_TESTS=1 ctest --test-dir build -L slow --output-on-failure
// SINEW_SLOW_FRAMES=K runs only the first K of the 24 stretch frames (same motion per frame).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "experiments/paper000_experiments.hpp"

namespace sinew {
namespace {

bool slow_enabled() {
  const char* v = std::getenv("SINEW_SLOW_TESTS");
  return v && std::string(v) == "1";
}

#define SINEW_REQUIRE_SLOW() \
  if (!slow_enabled()) GTEST_SKIP() << "full-size run: set SINEW_SLOW_TESTS=1 to run it"

ExperimentRun paper_stretch(const std::string& family, int newton_cap, int cg_cap) {
  StretchConfig c;
  c.family = family;
  c.solver = paper_solver(1e-3, newton_cap);
  c.solver.linear.max_iterations = cg_cap;
  ExperimentOptions o;
  if (const char* k = std::getenv("SINEW_SLOW_FRAMES")) o.frames = std::atoi(k);
  o.on_frame = [&](const ExperimentFrame& f) {
    std::printf("  %s frame %d: %s, %d Newton, %d CG, residual %.2e, volume %.5g, min J %.3f, %.0f s\n", family.c_str(),
                f.frame, f.converged ? "converged" : "NOT converged", f.newton_iterations, f.linear_iterations,
                f.residual, f.volume, f.min_quadrature_J, f.seconds);
    std::fflush(stdout);
  };
  const ExperimentRun run = run_experiment(stretch_scene(c), o);
  const auto paper = paper_stretch_figure(family);
  std::printf("stretch %s, %ld hexahedra (paper %ld): volume %+.2f %% (paper %+.1f %%), %d/%zu frames converged, "
              "%d Newton, %d CG, %.0f s\n",
              family.c_str(), static_cast<long>(run.elements), kPaperStretchHexes, run.volume_change_percent(),
              paper ? paper->volume_change_percent : 0.0, run.frames_converged(), run.frames.size(), run.total_newton(),
              run.total_linear(), run.seconds());
  return run;
}

TEST(ExperimentsSlow, StretchPaperSizeStableNeoHookean) {
  SINEW_REQUIRE_SLOW();
  const ExperimentRun run = paper_stretch("stable_neo_hookean", 100, 10000);
  EXPECT_EQ(run.frames_converged(), static_cast<int>(run.frames.size()));
  EXPECT_GT(run.volume_change_percent(), 0.0);
  EXPECT_LT(run.volume_change_percent(), 10.0);
  EXPECT_GT(run.frames.back().min_quadrature_J, 0.0);
}

TEST(ExperimentsSlow, StretchPaperSizeFilteredNeoHookean) {
  SINEW_REQUIRE_SLOW();
  const ExperimentRun run = paper_stretch("neo_hookean_filtered", 100, 10000);
  EXPECT_EQ(run.frames_converged(), static_cast<int>(run.frames.size()));
  EXPECT_GT(run.volume_change_percent(), 0.0);
  EXPECT_LT(run.volume_change_percent(), 10.0);
}

TEST(ExperimentsSlow, StretchPaperSizeFixedCorotational) {
  SINEW_REQUIRE_SLOW();
  const ExperimentRun run = paper_stretch("fixed_corotational", 100, 10000);
  EXPECT_EQ(run.frames_converged(), static_cast<int>(run.frames.size()));
  EXPECT_GT(run.volume_change_percent(), 0.0);
  EXPECT_LT(run.volume_change_percent(), 10.0);
}

// Co-rotational collapses; past about 2.4x our Newton does not converge within the caps
// (docs/experiments.md), so only the volume loss is asserted.
TEST(ExperimentsSlow, StretchPaperSizeCorotational) {
  SINEW_REQUIRE_SLOW();
  const ExperimentRun run = paper_stretch("corotational", 30, 2000);
  EXPECT_LT(run.volume_change_percent(), -50.0);
}

TEST(ExperimentsSlow, ScrambleTwentySeedsOnAnEightCube) {
  SINEW_REQUIRE_SLOW();
  int recovered = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    ScrambleConfig c;
    c.cells = 8;
    c.seed = seed;
    c.max_iterations = 10000;
    const ScrambleResult r = run_scramble(c);
    const bool rest = r.report.converged && r.max_error < 1e-4 * r.edge_length;
    recovered += rest ? 1 : 0;
    std::printf("scramble 8^3 seed %2llu: %d Newton, residual %.1e, max error %.1e, energy %.3g, min J %.3f: %s\n",
                static_cast<unsigned long long>(seed), r.report.iterations, r.report.residual, r.max_error, r.energy,
                r.min_quadrature_J, rest ? "rest shape" : (r.report.converged ? "another minimum" : "not converged"));
    std::fflush(stdout);
  }
  std::printf("scramble 8^3: %d of 20 recovered the rest shape\n", recovered);
  EXPECT_GE(recovered, 10);
}

}  // namespace
}  // namespace sinew
