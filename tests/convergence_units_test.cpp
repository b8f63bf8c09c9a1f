// The default (relative) convergence test does not depend on units or size: the same tissue
// cube in SI, in mm/N/MPa and scaled by 1e-3 and 1e3 in size and modulus gets the same
// displacements and (scaled) reactions, in similar Newton iteration counts. And a frame never
// "converges" at its starting point while far from equilibrium.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "sinew/model/model.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

using nlohmann::json;

// A cube of side `size` (2 mm of 10 kPa tissue in SI when size = 2e-3, E = 1e4): base pinned,
// top pulled up by 20 % over 2 frames and sheared by a traction of 5 % of E.
json tissue_cube(double size, double E) {
  const double s = size;
  json j = {
      {"mesh", {{"box", {{"min", {0, 0, 0}}, {"max", {s, s, s}}}}, {"cells", {3, 3, 3}}}},
      {"material", {{"family", "stable_neo_hookean"}, {"E", E}, {"nu", 0.45}}},
      {"boundary",
       {{{"name", "base"}, {"select", {{"plane", {{"point", {0, 0, 0}}, {"normal", {0, 0, -1}}}}}}},
        {{"name", "top"},
         {"select", {{"plane", {{"point", {0, 0, s}}, {"normal", {0, 0, 1}}}}}},
         {"components", {"z"}},
         {"motion", {{"type", "displace"}, {"displacement", {0, 0, 0.2 * s}}}}}}},
      {"loads",
       {{"traction",
         {{{"select", {{"plane", {{"point", {0, 0, s}}, {"normal", {0, 0, 1}}}}}}, {"traction", {0.05 * E, 0, 0}}}}}}},
      {"frames", 2}};
  return j;
}

struct Units {
  const char* name;
  double length;   // size of the cube
  double modulus;  // E
};

TEST(ConvergenceUnits, SameAnswerInAnyUnitsAndAtAnyScale) {
  const Units cases[] = {{"SI (m, Pa)", 2e-3, 1e4},          {"mm, N, MPa", 2.0, 1e-2},
                         {"SI x 1e-3 size and modulus", 2e-6, 1e1}, {"SI x 1e3 size and modulus", 2.0, 1e7},
                         {"SI x 1e3 size, 1e-3 modulus", 2.0, 1e1}};
  std::vector<RunSummary> runs;
  for (const Units& u : cases) {
    runs.push_back(run_scene(parse_scene(tissue_cube(u.length, u.modulus), "cube.json"), RunOptions{}));
    const RunSummary& r = runs.back();
    ASSERT_EQ(r.frames.size(), 2u) << u.name;
    for (const FrameRecord& f : r.frames) {
      EXPECT_TRUE(f.converged) << u.name << ": " << f.failure;
      EXPECT_GE(f.newton_iterations, 2) << u.name;  // never stops at the start
    }
  }
  // Compare in units of the case: displacement / size, force / (E size^2).
  for (size_t c = 1; c < runs.size(); ++c) {
    const double L0 = cases[0].length, L = cases[c].length;
    const double F0 = cases[0].modulus * L0 * L0, F = cases[c].modulus * L * L;
    const Eigen::VectorXd a = runs[0].x / L0, b = runs[c].x / L;
    EXPECT_LT((a - b).lpNorm<Eigen::Infinity>(), 1e-6) << cases[c].name;
    for (size_t k = 0; k < 2; ++k) {
      const FrameRecord &f0 = runs[0].frames[k], &f = runs[c].frames[k];
      for (size_t i = 0; i < f0.reactions.size(); ++i)
        EXPECT_LT((f0.reactions[i] / F0 - f.reactions[i] / F).norm(), 1e-6 * (1.0 + f0.reactions[i].norm() / F0))
            << cases[c].name << " frame " << k + 1 << " reaction " << i;
      EXPECT_LE(std::abs(f.newton_iterations - f0.newton_iterations), 2) << cases[c].name << " frame " << k + 1;
    }
  }
  // The top's support pulls the body up (the sign the SI case got wrong under an absolute
  // 1e-2 N tolerance), and more in frame 2 than in frame 1.
  EXPECT_GT(runs[0].frames[0].reactions[1](2), 0.0);
  EXPECT_GT(runs[0].frames[1].reactions[1](2), runs[0].frames[0].reactions[1](2));
}

// Paper 000's absolute tolerance on the same SI cube stops too early (the forces are ~1e-3 N):
// the reason the default is relative. Kept as a measurement of that failure.
TEST(ConvergenceUnits, AbsoluteToleranceInSIStopsEarly) {
  json j = tissue_cube(2e-3, 1e4);
  j["solver"] = {{"newton", {{"convergence", "absolute"}, {"tolerance", 1e-2}}}};
  const RunSummary absolute = run_scene(parse_scene(j, "cube.json"), RunOptions{});
  const RunSummary relative = run_scene(parse_scene(tissue_cube(2e-3, 1e4), "cube.json"), RunOptions{});
  ASSERT_EQ(absolute.frames.size(), 2u);
  EXPECT_LE(absolute.frames[0].newton_iterations, 2);
  const double err = (absolute.x - relative.x).lpNorm<Eigen::Infinity>() / 2e-3;
  EXPECT_GT(err, 1e-3);  // a visibly wrong answer reported as converged
}

}  // namespace
}  // namespace sinew
