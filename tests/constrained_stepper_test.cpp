// Paper 001 §5-6: the constrained backward-Euler step on the beam and the falling sphere.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "sinew/constraints/corotational_hex.hpp"
#include "sinew/constraints/paper001_experiments.hpp"
#include "sinew/fem/mass.hpp"
#include "sinew/mesh/lattice.hpp"

namespace sinew {
namespace {

using namespace paper001;

TEST(Paper001Meshes, BeamAndSphereHaveThePapersElementCounts) {
  const VolumeMesh beam = beam_mesh();
  EXPECT_EQ(beam.num_elements(), 56);
  EXPECT_NEAR(beam.vertices.col(0).maxCoeff() - beam.vertices.col(0).minCoeff(), 1.0, 1e-12);
  EXPECT_NEAR(beam.vertices.col(1).maxCoeff() - beam.vertices.col(1).minCoeff(), 0.12, 1e-12);
  const VolumeMesh sphere = sphere_mesh(Eigen::Vector3d::Zero(), 1.0, 3);
  EXPECT_EQ(sphere.num_elements(), 27);
  for (Eigen::Index v = 0; v < sphere.num_vertices(); ++v) EXPECT_LE(sphere.vertices.row(v).norm(), 1.0 + 1e-12);
}

TEST(ConstrainedStepper, FreeFallWithoutConstraintsIsBackwardEuler) {
  // A rigid free fall has no elastic force: v = v0 + h g exactly, every step.
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), Eigen::Vector3i(1, 1, 1));
  auto model = std::make_shared<CorotationalHex>(std::make_shared<Discretization>(mesh),
                                                 HookeCoefficients::from_young_poisson(1e5, 0.3));
  const Eigen::VectorXd masses = lumped_mass(model->discretization(), 100.0);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(24);
  for (int v = 0; v < 8; ++v) f(3 * v + 2) = -9.81 * masses(v);
  ConstrainedStepSettings s;
  s.time_step = 0.02;
  ConstrainedStepper stepper(model, masses, f, std::vector<char>(24, 0), {}, s);
  Eigen::VectorXd x = mesh.rest_positions(), v = Eigen::VectorXd::Zero(24);
  for (int k = 1; k <= 5; ++k) {
    const ConstrainedStepReport r = stepper.step(x, v);
    EXPECT_TRUE(r.converged);
    EXPECT_EQ(r.sqp_iterations, 0);
    for (int i = 0; i < 8; ++i) EXPECT_NEAR(v(3 * i + 2), -9.81 * 0.02 * k, 1e-9);
  }
}

TEST(ConstrainedStepper, BeamDeflectionFallsWithTheEnergyLimitAndLimitsHold) {
  // Fig. 3: linear 150 kPa, limited 1.0 / 0.5 / 0.1 J, linear 2 MPa.
  struct Case {
    const char* name;
    double young;
    std::optional<double> limit;
  };
  const std::vector<Case> cases = {{"linear 150 kPa", 150e3, {}},
                                   {"150 kPa, U_e <= 1.0 J", 150e3, 1.0},
                                   {"150 kPa, U_e <= 0.5 J", 150e3, 0.5},
                                   {"150 kPa, U_e <= 0.1 J", 150e3, 0.1},
                                   {"linear 2 MPa", 2e6, {}}};
  std::vector<double> deflection;
  for (const Case& c : cases) {
    BeamConfig config;
    config.young = c.young;
    config.max_energy = c.limit;
    config.duration = 1.5;
    const BeamResult r = run_beam(config);
    fmt::print("beam {:<24} max tip deflection {:.4f} m, max U_e {:.4f} J, SQP {} PGS {} unconverged {} ({:.2f} ms/step)\n",
               c.name, r.max_tip_deflection, r.totals.max_element_energy, r.totals.sqp_iterations,
               r.totals.pgs_iterations, r.totals.unconverged_steps, r.totals.ms_per_step());
    deflection.push_back(r.max_tip_deflection);
    if (c.limit) {
      EXPECT_EQ(r.totals.unconverged_steps, 0) << c.name;
      EXPECT_LE(r.totals.max_element_energy, *c.limit * (1.0 + config.solver.energy_tolerance)) << c.name;
    }
  }
  for (size_t i = 1; i < deflection.size(); ++i) EXPECT_LT(deflection[i], deflection[i - 1]) << cases[i].name;
}

TEST(ConstrainedStepper, FallingSphereRestsOnFrictionalGround) {
  // Fig. 4 (27 hexahedra): all three land without penetration beyond tolerance; the energy
  // limit keeps the compliant sphere from being compressed as much as the linear one.
  struct Case {
    const char* name;
    double young;
    std::optional<double> limit;
  };
  std::vector<SphereResult> results;
  for (const Case& c : {Case{"linear 150 kPa", 150e3, {}}, Case{"linear 1 MPa", 1e6, {}},
                        Case{"150 kPa, U_e <= 500 J", 150e3, 500.0}}) {
    SphereConfig config;
    config.young = c.young;
    config.max_energy = c.limit;
    config.duration = 2.0;
    const SphereResult r = run_falling_sphere(config);
    fmt::print("sphere {:<24} peak compression {:.1f} %, rebound {:.3f} m, max U_e {:.1f} J, penetration {:.2e} m, "
               "SQP {} PGS {} unconverged {} ({:.2f} ms/step)\n",
               c.name, 100 * r.peak_compression, r.rebound_height, r.totals.max_element_energy, r.max_penetration,
               r.totals.sqp_iterations, r.totals.pgs_iterations, r.totals.unconverged_steps, r.totals.ms_per_step());
    EXPECT_EQ(r.totals.unconverged_steps, 0) << c.name;
    EXPECT_LE(r.max_penetration, config.solver.contact_tolerance) << c.name;
    EXPECT_GT(r.peak_compression, 0.0) << c.name;
    results.push_back(r);
  }
  EXPECT_LT(results[1].peak_compression, results[0].peak_compression);
  EXPECT_LT(results[2].peak_compression, results[0].peak_compression);
  EXPECT_LE(results[2].totals.max_element_energy, 500.0 * (1.0 + SphereConfig{}.solver.energy_tolerance));
}

}  // namespace
}  // namespace sinew
