// Paper 001 Fig. 5: the high-resolution collapsing sphere (Y = 50 kPa, U_e <= 50 J), linear vs
// energy-limited. Label `slow`; skips itself unless SINEW_SLOW_TESTS=1:
//   SINEW_SLOW_TESTS=1 build/tests/sinew_slow_tests --gtest_filter='CollapsingSphere*'
#include <gtest/gtest.h>

#include <cstdlib>
#include <fmt/format.h>
#include <string>

#include "experiments/paper001_experiments.hpp"

namespace sinew {
namespace {

bool slow_enabled() {
  const char* v = std::getenv("SINEW_SLOW_TESTS");
  return v && std::string(v) == "1";
}

TEST(CollapsingSphere, EnergyLimitHoldsTheHighResolutionSphereUp) {
  if (!slow_enabled()) GTEST_SKIP() << "set SINEW_SLOW_TESTS=1 to run it";
  paper001::SphereResult results[2];
  for (int k = 0; k < 2; ++k) {
    paper001::SphereConfig config;
    config.young = 50e3;
    config.cells = 10;
    config.duration = 2.0;
    if (k == 1) config.max_energy = 50.0;
    results[k] = paper001::run_falling_sphere(config);
    const auto& r = results[k];
    fmt::print("{} hexahedra, {}: peak compression {:.1f} %, rebound {:.3f} m, max U_e {:.2f} J, penetration {:.2e} m, "
               "SQP {} PGS {} unconverged {}, {:.2f} ms/step\n",
               r.elements, k ? "U_e <= 50 J" : "linear", 100 * r.peak_compression, r.rebound_height,
               r.totals.max_element_energy, r.max_penetration, r.totals.sqp_iterations, r.totals.pgs_iterations,
               r.totals.unconverged_steps, r.totals.ms_per_step());
    EXPECT_EQ(r.totals.unconverged_steps, 0);
    EXPECT_LE(r.max_penetration, config.solver.contact_tolerance);
  }
  EXPECT_LE(results[1].totals.max_element_energy, 50.0 * (1 + paper001::SphereConfig{}.solver.energy_tolerance));
  EXPECT_LT(results[1].peak_compression, results[0].peak_compression);
}

}  // namespace
}  // namespace sinew
