#include "sinew/model/model.hpp"

#include <fmt/format.h>

#include "sinew/constraints/obstacle_contacts.hpp"
#include "sinew/core/error.hpp"
#include "sinew/element/mass.hpp"
#include "sinew/forms/corotational_hex_form.hpp"
#include "sinew/forms/external_force_form.hpp"
#include "sinew/integrator/energy_limited_integrator.hpp"
#include "sinew/integrator/implicit_dynamics_integrator.hpp"
#include "sinew/integrator/quasistatic_integrator.hpp"

namespace sinew {
namespace {

// Consistent nodal forces of a uniform traction t on the boundary faces whose vertices are all
// selected: f_a = t * integral over the rest face of N_a (area / 3 per corner of a triangle;
// bilinear quads by 2x2 Gauss, which is exact for their rest area). Throws if no face qualifies.
Eigen::VectorXd traction_forces(const VolumeMesh& mesh, const BoundarySurface& surface,
                                const std::vector<int>& selected, const Eigen::Vector3d& traction,
                                const std::string& context) {
  std::vector<char> in(mesh.num_vertices(), 0);
  for (int v : selected) in[v] = 1;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.num_vertices());
  int faces = 0;
  for (const auto& face : surface.faces) {
    if (!std::all_of(face.begin(), face.end(), [&](int v) { return in[v] != 0; })) continue;
    ++faces;
    auto p = [&](int k) -> Eigen::Vector3d { return mesh.vertices.row(face[k]).transpose(); };
    if (face.size() == 3) {
      const double area = 0.5 * (p(1) - p(0)).cross(p(2) - p(0)).norm();
      for (int v : face) f.segment<3>(3 * v) += area / 3.0 * traction;
      continue;
    }
    const double g = 0.5 / std::sqrt(3.0);  // Gauss points 0.5 -+ g on [0, 1]
    for (double u : {0.5 - g, 0.5 + g})
      for (double w : {0.5 - g, 0.5 + g}) {
        const double N[4] = {(1 - u) * (1 - w), u * (1 - w), u * w, (1 - u) * w};
        const Eigen::Vector3d du = (1 - w) * (p(1) - p(0)) + w * (p(2) - p(3));
        const Eigen::Vector3d dw = (1 - u) * (p(3) - p(0)) + u * (p(2) - p(1));
        const double jac = 0.25 * du.cross(dw).norm();  // weight 1/4 per point on the unit square
        for (int k = 0; k < 4; ++k) f.segment<3>(3 * face[k]) += jac * N[k] * traction;
      }
  }
  if (faces == 0) throw Error("selects no boundary face (a traction acts on faces whose vertices are all selected)", context);
  return f;
}

// The elastic form: the scene's material, or corotational hexahedra for the energy-limited
// "corotational" model.
void build_elastic(const Scene& scene, Model& m) {
  const std::string file = scene.file.string();
  const bool corotational = scene.constraints && scene.constraints->model == "corotational";
  if (corotational) {
    if (m.disc->mesh().kind != ElementKind::Hex8)
      throw Error("the corotational model needs hexahedra (mesh element \"hex\")", file + ": /constraints/model");
    // Hookean coefficients from the material's small-strain Lame parameters: E1 = lambda + 2 mu,
    // E2 = lambda, E3 = mu (paper 001 §4.2).
    const double lambda = m.material.lame.lambda, mu = m.material.lame.mu;
    m.elastic = std::make_shared<CorotationalHexForm>(m.disc, HookeCoefficients{lambda + 2 * mu, lambda, mu});
  } else {
    // The energy-limited stepper's Hessian is clamped per quadrature point, as before forms.
    const Projection projection = scene.constraints ? Projection::Clamp : scene.solver.projection;
    m.hyperelastic = std::make_shared<ElasticForm>(m.disc, m.material.material, projection);
    m.elastic = m.hyperelastic;
  }
}

// The scene's boundary conditions; a vertex moved by two different motions has no
// well-defined position.
void build_boundary(const Scene& scene, Model& m) {
  const std::string file = scene.file.string();
  const VolumeMesh& mesh = m.disc->mesh();
  std::vector<int>& owner = m.boundary_owner;
  owner.assign(mesh.num_vertices(), -1);
  for (size_t i = 0; i < scene.boundary.size(); ++i) {
    const auto& b = scene.boundary[i];
    const std::string where = fmt::format("{}: /boundary/{}/select", file, i);
    KinematicCondition c{select_vertices(mesh.vertices, b.select, where), b.motion};
    for (int v : c.vertices) {
      if (owner[v] >= 0 && !(std::holds_alternative<Pinned>(b.motion) &&
                             std::holds_alternative<Pinned>(scene.boundary[owner[v]].motion)))
        throw Error(fmt::format("vertex {} is also selected by /boundary/{} with a different motion", v, owner[v]), where);
      if (owner[v] < 0) owner[v] = static_cast<int>(i);
    }
    m.kinematics.push_back(std::move(c));
  }
}

std::shared_ptr<PenaltyContactForm> penalty_contact(const Scene& scene, const Model& m) {
  if (scene.obstacles.empty()) return nullptr;
  std::vector<std::shared_ptr<const Obstacle>> obstacles;
  std::vector<ContactParameters> params;
  for (const auto& o : scene.obstacles) {
    obstacles.push_back(std::make_shared<Obstacle>(o.name, o.shape, o.motion));
    params.push_back(o.contact);
  }
  return std::make_shared<PenaltyContactForm>(obstacles, params, m.surface.vertices,
                                              boundary_vertex_areas(m.disc->mesh(), m.surface));
}

}  // namespace

void Model::prescribe(double frame, Eigen::VectorXd& x, std::vector<char>& fixed) const {
  const Eigen::MatrixX3d& rest = disc->mesh().vertices;
  apply_kinematics(kinematics, rest, frame, x, fixed);
  rig.apply(frame, rest, x, fixed);
}

Eigen::VectorXd external_forces(const Scene& scene, const Discretization& disc, const BoundarySurface& surface) {
  const std::string file = scene.file.string();
  const VolumeMesh& mesh = disc.mesh();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(disc.num_dofs());
  if (scene.gravity.squaredNorm() > 0.0) f += gravity_forces(lumped_mass(disc, scene.density), scene.gravity);
  for (size_t i = 0; i < scene.point_loads.size(); ++i) {
    for (int v : select_vertices(mesh.vertices, scene.point_loads[i].select, fmt::format("{}: /loads/point/{}/select", file, i)))
      f.segment<3>(3 * v) += scene.point_loads[i].force;
  }
  for (size_t i = 0; i < scene.tractions.size(); ++i) {
    const std::string where = fmt::format("{}: /loads/traction/{}/select", file, i);
    f += traction_forces(mesh, surface, select_vertices(mesh.vertices, scene.tractions[i].select, where),
                         scene.tractions[i].traction, where);
  }
  return f;
}

Model build_model(const Scene& scene) {
  const std::string file = scene.file.string();
  Model m;
  m.disc = std::make_shared<Discretization>(build_scene_mesh(scene), file + ": /mesh");
  const VolumeMesh& mesh = m.disc->mesh();
  m.material = build_material_detailed(scene.material);
  build_elastic(scene, m);
  m.problem = std::make_shared<Problem>(mesh.num_vertices());
  m.problem->add_form(m.elastic);
  m.surface = boundary_surface(mesh);
  m.external_forces = external_forces(scene, *m.disc, m.surface);
  if (m.external_forces.squaredNorm() > 0.0) m.problem->add_form(std::make_shared<ExternalForceForm>(m.external_forces));
  build_boundary(scene, m);
  m.rig = make_scene_rig(scene, mesh, *m.problem);  // bone springs and self-contact forms
  m.initial.x = mesh.rest_positions();
  // Captures copies: the model is returned by value.
  PrescribedMotion motion = [kinematics = m.kinematics, rest = mesh.vertices, rig = m.rig](
                                double frame, Eigen::VectorXd& x, std::vector<char>& fixed) {
    apply_kinematics(kinematics, rest, frame, x, fixed);
    rig.apply(frame, rest, x, fixed);
  };

  if (scene.constraints) {  // energy-limited dynamics (the scene reader requires `dynamics` with it)
    const ConstraintsSpec& spec = *scene.constraints;
    const DynamicsSpec& dynamics = *scene.dynamics;
    m.energy_limit = spec.step.energy_limit;
    m.lumped_masses = lumped_mass(*m.disc, scene.density);
    ContactProvider contacts;
    if (!scene.obstacles.empty()) {
      std::vector<ObstacleContact> obstacles;
      for (const ObstacleSpec& o : scene.obstacles)
        obstacles.push_back({std::make_shared<Obstacle>(o.name, o.shape, o.motion), o.contact.friction});
      contacts = obstacle_contacts(std::move(obstacles), m.surface.vertices, spec.contact_margin, dynamics.time_step);
    }
    auto stepper = std::make_unique<EnergyLimitedStepper>(m.problem, m.elastic, m.lumped_masses, contacts, spec.step);
    m.integrator = std::make_unique<EnergyLimitedIntegrator>(std::move(stepper), std::move(motion), dynamics.substeps);
    // The initial velocity moves every vertex that is not prescribed at the start.
    Eigen::VectorXd x0 = m.initial.x;
    std::vector<char> fixed(x0.size(), 0);
    m.prescribe(0.0, x0, fixed);
    m.initial.v = Eigen::VectorXd::Zero(x0.size());
    for (Eigen::Index i = 0; i < mesh.num_vertices(); ++i)
      if (!fixed[3 * i]) m.initial.v.segment<3>(3 * i) = dynamics.initial_velocity;
    return m;
  }

  m.contact = penalty_contact(scene, m);
  if (m.contact) m.problem->add_form(m.contact);
  if (!scene.dynamics) {
    m.integrator = std::make_unique<QuasistaticIntegrator>(m.problem, std::move(motion), m.contact,
                                                           make_linear_solver(scene.solver.linear), scene.solver.newton);
    return m;
  }
  const DynamicsSpec& d = *scene.dynamics;
  const double h = d.time_step / d.substeps;
  m.mass = std::make_shared<MassMatrix>(*m.disc, scene.density, d.mass);
  m.lumped_masses = m.mass->lumped();
  auto inertia = std::make_shared<InertiaForm>(m.mass, h);
  m.problem->add_form(inertia);
  std::shared_ptr<DampingForm> damping;
  if (d.rayleigh_alpha > 0.0 || d.rayleigh_beta > 0.0) {
    damping = std::make_shared<DampingForm>(m.mass, m.elastic, mesh.num_vertices(), d.rayleigh_alpha, d.rayleigh_beta, h);
    m.problem->add_form(damping);
  }
  TimeStepSettings settings;
  settings.integrator = d.integrator;
  settings.newton = scene.solver.newton;
  settings.friction_velocity = d.friction_velocity;
  auto stepper = std::make_unique<TimeStepper>(*m.problem, inertia, damping, m.contact, std::vector<KinematicCondition>{},
                                               mesh.vertices, settings);
  stepper->add_kinematic_hook([motion](double frame, const Eigen::MatrixX3d&, Eigen::VectorXd& x,
                                       std::vector<char>& fixed) { motion(frame, x, fixed); });
  m.integrator = std::make_unique<ImplicitDynamicsIntegrator>(m.problem, std::move(stepper),
                                                              make_linear_solver(scene.solver.linear), d.integrator,
                                                              d.substeps);
  m.initial.v = d.initial_velocity.replicate(mesh.num_vertices(), 1);
  return m;
}

}  // namespace sinew
