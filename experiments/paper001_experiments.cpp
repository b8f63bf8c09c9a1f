#include "experiments/paper001_experiments.hpp"

#include <cmath>

#include "sinew/element/mesh_validation.hpp"
#include "sinew/forms/corotational_hex_form.hpp"
#include "sinew/element/mass.hpp"
#include "sinew/mesh/lattice.hpp"

namespace sinew::paper001 {

VolumeMesh beam_mesh() {
  const double r = 0.06, length = 1.0;
  return occupancy_lattice(Eigen::AlignedBox3d(Eigen::Vector3d(0, -r, -r), Eigen::Vector3d(length, r, r)),
                           Eigen::Vector3i(14, 2, 2),
                           [sdf = cylinder_sdf(Eigen::Vector3d(length / 2, 0, 0), r, length, 0)](
                               const Eigen::Vector3d& p) { return sdf(p) < 0.0; });
}

VolumeMesh sphere_mesh(const Eigen::Vector3d& center, double radius, int cells) {
  const Eigen::Vector3d lo = center - Eigen::Vector3d::Constant(radius), hi = center + Eigen::Vector3d::Constant(radius);
  if (cells != 3) {
    VolumeMesh m = occupancy_lattice(Eigen::AlignedBox3d(lo, hi), Eigen::Vector3i::Constant(cells),
                                     [sdf = sphere_sdf(center, radius)](const Eigen::Vector3d& p) { return sdf(p) < 0.0; });
    validate_mesh(m, "sphere");
    return m;
  }
  VolumeMesh m = box_lattice(lo, hi, Eigen::Vector3i::Constant(3));
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v) {
    const Eigen::Vector3d p = m.vertices.row(v).transpose() - center;
    const double n2 = p.norm();
    if (n2 > 0.0) m.vertices.row(v) = (center + p * (p.cwiseAbs().maxCoeff() / n2)).transpose();
  }
  validate_mesh(m, "sphere");
  return m;
}

namespace {

std::shared_ptr<CorotationalHexForm> corotational(const VolumeMesh& mesh, double young, double poisson) {
  return std::make_shared<CorotationalHexForm>(std::make_shared<Discretization>(mesh, "paper001"),
                                           HookeCoefficients::from_young_poisson(young, poisson));
}

EnergyLimitedStepSettings step_settings(EnergyLimitedStepSettings s, double h, std::optional<double> max_energy,
                                      JacobianKind jacobian) {
  s.time_step = h;
  if (max_energy) s.energy_limit = EnergyLimit{*max_energy, jacobian};
  else s.energy_limit.reset();
  return s;
}

int step_count(double duration, double h) { return static_cast<int>(std::lround(duration / h)); }

}  // namespace

BeamResult run_beam(const BeamConfig& c) {
  const VolumeMesh mesh = beam_mesh();
  auto model = corotational(mesh, c.young, c.poisson);
  const Discretization& disc = model->discretization();
  const Eigen::VectorXd masses = lumped_mass(disc, c.density);
  const Eigen::Index n = disc.num_dofs();
  Eigen::VectorXd gravity = Eigen::VectorXd::Zero(n);
  std::vector<char> fixed(n, 0);
  std::vector<int> tip;
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
    gravity(3 * v + 2) = -9.81 * masses(v);
    if (mesh.vertices(v, 0) < 1e-9) fixed[3 * v] = fixed[3 * v + 1] = fixed[3 * v + 2] = 1;
    if (mesh.vertices(v, 0) > 1.0 - 1e-9) tip.push_back(static_cast<int>(v));
  }
  EnergyLimitedStepper stepper(model, masses, gravity, fixed, {}, step_settings(c.solver, c.time_step, c.max_energy, c.jacobian));
  Eigen::VectorXd x = mesh.rest_positions(), v = Eigen::VectorXd::Zero(n);
  BeamResult result;
  auto tip_z = [&](const Eigen::VectorXd& y) {
    double z = 0.0;
    for (int t : tip) z += y(3 * t + 2);
    return z / static_cast<double>(tip.size());
  };
  const double z0 = tip_z(x);
  for (int s = 0, steps = step_count(c.duration, c.time_step); s < steps; ++s) {
    result.totals.add(stepper.step(x, v));
    result.max_tip_deflection = std::max(result.max_tip_deflection, z0 - tip_z(x));
  }
  return result;
}

SphereResult run_falling_sphere(const SphereConfig& c) {
  const VolumeMesh mesh = sphere_mesh(Eigen::Vector3d(0, 0, c.radius + c.drop_height), c.radius, c.cells);
  auto model = corotational(mesh, c.young, c.poisson);
  const Discretization& disc = model->discretization();
  const Eigen::VectorXd masses = lumped_mass(disc, c.density);
  const Eigen::Index n = disc.num_dofs();
  Eigen::VectorXd gravity = Eigen::VectorXd::Zero(n), v = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < mesh.num_vertices(); ++i) {
    gravity(3 * i + 2) = -9.81 * masses(i);
    v.segment<3>(3 * i) = c.initial_velocity;
  }
  const double margin = 0.05 * c.radius;
  EnergyLimitedStepper stepper(model, masses, gravity, std::vector<char>(n, 0),
                             ground_plane_contacts(Eigen::Vector3d::UnitZ(), 0.0, c.friction, margin),
                             step_settings(c.solver, c.time_step, c.max_energy, JacobianKind::Exact));
  Eigen::VectorXd x = mesh.rest_positions();
  auto extent = [](const Eigen::VectorXd& y) {
    const auto z = y.reshaped(3, y.size() / 3).row(2);
    return std::make_pair(z.minCoeff(), z.maxCoeff());
  };
  const auto [lo0, hi0] = extent(x);
  SphereResult result;
  result.elements = static_cast<int>(mesh.num_elements());
  bool touched = false, left = false;
  for (int s = 0, steps = step_count(c.duration, c.time_step); s < steps; ++s) {
    const EnergyLimitedStepReport r = stepper.step(x, v);
    result.totals.add(r);
    result.max_penetration = std::max(result.max_penetration, r.penetration);
    const auto [lo, hi] = extent(x);
    result.peak_compression = std::max(result.peak_compression, 1.0 - (hi - lo) / (hi0 - lo0));
    // Rebound: the lowest point's height once the body has left the ground after first contact.
    const bool contact = lo < 1e-3 * c.radius;
    if (contact) touched = true;
    if (touched && !contact) left = true;
    if (left) result.rebound_height = std::max(result.rebound_height, lo);
  }
  return result;
}

}  // namespace sinew::paper001
