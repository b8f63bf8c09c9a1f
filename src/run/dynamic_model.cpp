#include "sinew/run/dynamic_model.hpp"

#include <fmt/format.h>

namespace sinew {

DynamicModel build_dynamic_model(const Scene& scene, const std::shared_ptr<const Discretization>& disc,
                                 const std::shared_ptr<const Form>& elastic, const BoundarySurface& surface,
                                 Problem& problem, const std::vector<KinematicCondition>& kinematics) {
  DynamicModel m;
  const VolumeMesh& mesh = disc->mesh();
  if (!scene.obstacles.empty()) {
    std::vector<std::shared_ptr<const Obstacle>> obstacles;
    std::vector<ContactParameters> params;
    for (const auto& o : scene.obstacles) {
      obstacles.push_back(std::make_shared<Obstacle>(o.name, o.shape, o.motion));
      params.push_back(o.contact);
    }
    m.contact = std::make_shared<PenaltyContactForm>(obstacles, params, surface.vertices,
                                                     boundary_vertex_areas(mesh, surface));
    problem.add_form(m.contact);
  }
  if (!scene.dynamics) return m;
  const DynamicsSpec& d = *scene.dynamics;
  const double h = d.time_step / d.substeps;
  m.mass = std::make_shared<MassMatrix>(*disc, scene.density, d.mass);
  m.inertia = std::make_shared<InertiaForm>(m.mass, h);
  problem.add_form(m.inertia);
  if (d.rayleigh_alpha > 0.0 || d.rayleigh_beta > 0.0) {
    m.damping = std::make_shared<DampingForm>(m.mass, elastic, mesh.num_vertices(), d.rayleigh_alpha, d.rayleigh_beta, h);
    problem.add_form(m.damping);
  }
  TimeStepSettings settings;
  settings.integrator = d.integrator;
  settings.newton = scene.solver.newton;
  settings.friction_velocity = d.friction_velocity;
  m.stepper = std::make_unique<TimeStepper>(problem, m.inertia, m.damping, m.contact, kinematics, mesh.vertices, settings);
  m.v = d.initial_velocity.replicate(mesh.num_vertices(), 1);
  return m;
}

void advance_dynamic_frame(DynamicModel& model, const Scene& scene, Eigen::VectorXd& x, int frame,
                           LinearSolver& linear, FrameRecord& record,
                           const std::function<void(const NewtonIterate&)>& progress) {
  const int n = scene.dynamics->substeps;
  record.substeps = 0;
  for (int s = 1; s <= n; ++s) {
    const double frame0 = frame - 1 + double(s - 1) / n, frame1 = frame - 1 + double(s) / n;
    const StepReport r = model.stepper->step(x, model.v, frame0, frame1, linear, progress);
    record.newton_iterations += r.newton_iterations;
    record.linear_iterations += r.linear_iterations;
    record.assembly_seconds += r.assembly_seconds;
    record.solve_seconds += r.solve_seconds;
    record.residual = r.residual;
    record.energy = r.energy;
    if (!r.converged) {
      record.failure = fmt::format("time step {} of {} ({}): {}", s, n, to_string(scene.dynamics->integrator), r.failure);
      return;
    }
    record.substeps += 1;
  }
}

void record_energies(const DynamicModel& model, const Form& elastic, const Eigen::VectorXd& forces,
                     const Eigen::VectorXd& x, FrameRecord& record) {
  record.potential_energy = elastic.value(x) - forces.dot(x);
  if (model.contact) {
    const ContactStats s = model.contact->stats(x);
    record.potential_energy += s.penalty_energy;
    record.contacts = s.contacts;
    record.max_penetration = s.max_penetration;
  }
  record.kinetic_energy = model.mass ? model.mass->kinetic_energy(model.v) : 0.0;
}

}  // namespace sinew
