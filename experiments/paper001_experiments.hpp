#pragma once
// The animation tests of paper 001 §6 as plain functions, shared by tests, the benchmark and
// the docs: the cantilever beam (Fig. 3, §6.2 Jacobian comparison), the falling sphere
// (Fig. 4) and the collapsing high-resolution sphere (Fig. 5).
#include <optional>
#include <vector>

#include "sinew/integrator/energy_limited_stepper.hpp"
#include "sinew/mesh/volume_mesh.hpp"

namespace sinew::paper001 {

// 1 m x 12 cm x 12 cm cylindrical beam along x, 14 x 2 x 2 = 56 hexahedra (every cell of the
// grid over the cylinder's bounding box has its centre inside the cylinder).
VolumeMesh beam_mesh();
// Sphere of radius R centred at c: the 3 x 3 x 3 = 27-hexahedron lattice of its bounding cube,
// vertices pushed radially onto concentric spheres (p -> p |p|_inf / |p|_2), when cells == 3;
// for a finer resolution, the cells of a cells^3 grid whose centre lies inside the sphere.
VolumeMesh sphere_mesh(const Eigen::Vector3d& center, double radius, int cells);

// Sums over the steps of a run (constrained_stepper.hpp).
using Totals = EnergyLimitedStepTotals;

struct BeamConfig {
  double young = 150e3, poisson = 0.3, density = 500.0;
  std::optional<double> max_energy;  // J per element
  JacobianKind jacobian = JacobianKind::Exact;
  double time_step = 0.01, duration = 2.0;
  EnergyLimitedStepSettings solver;  // time_step and energy_limit are filled in from the fields above
};
struct BeamResult {
  double max_tip_deflection = 0.0;  // max over time of the tip centre's downward displacement (m)
  Totals totals;
};
BeamResult run_beam(const BeamConfig& config);

struct SphereConfig {
  double radius = 1.0, drop_height = 2.0;  // lowest point starts drop_height above the ground
  int cells = 3;
  double young = 150e3, poisson = 0.3, density = 500.0, friction = 0.5;
  Eigen::Vector3d initial_velocity = Eigen::Vector3d::Zero();
  std::optional<double> max_energy;
  double time_step = 0.01, duration = 3.0;
  EnergyLimitedStepSettings solver;
};
struct SphereResult {
  double peak_compression = 0.0;  // max over time of 1 - (vertical extent / rest extent)
  double rebound_height = 0.0;    // highest lowest-point after the first contact ended (m)
  double max_penetration = 0.0;   // over the steps' final states (m)
  int elements = 0;
  Totals totals;
};
SphereResult run_falling_sphere(const SphereConfig& config);

}  // namespace sinew::paper001
