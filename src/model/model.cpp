#include "sinew/model/model.hpp"

#include <fmt/format.h>
#include <numbers>

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

// Follower pressures on the boundary faces whose vertices are all selected.
void build_pressures(const Scene& scene, Model& m) {
  const VolumeMesh& mesh = m.disc->mesh();
  for (size_t i = 0; i < scene.pressures.size(); ++i) {
    const std::string where = fmt::format("{}: /loads/pressure/{}/select", scene.file.string(), i);
    auto faces = faces_within(m.surface, select_vertices(mesh, scene.pressures[i].select, where), mesh.num_vertices());
    if (faces.empty()) throw Error("selects no boundary face (a pressure acts on faces whose vertices are all selected)", where);
    m.pressures.push_back(std::make_shared<PressureForm>(std::move(faces), mesh.rest_positions(), scene.pressures[i].pressure));
    m.pressure_amplitudes.push_back(scene.pressures[i].amplitude);
    m.pressures.back()->set_scale(scene.pressures[i].amplitude.at(1.0));  // as the other loads: frame 1 until a frame is set
    m.problem->add_form(m.pressures.back());
  }
}

// The elastic form: the scene's material, or corotational hexahedra for the energy-limited
// "corotational" model.
// Scales for dimensionless convergence tests: the body's size (bounding-box diagonal) and the
// force that strains it by one (shear modulus x size^2).
Problem::Scales problem_scales(const VolumeMesh& mesh, const Lame& lame) {
  const double size = (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).norm();
  return {size, std::abs(lame.mu) * size * size};
}

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

// The scene's boundary conditions. Each prescribes all coordinates of its vertices, some of them,
// or the motion along one direction. A coordinate (or direction) prescribed twice must be pinned
// both times: two motions of one coordinate have no well-defined position. A vertex with a
// direction that is not a coordinate axis gets a rotated frame whose first axes are its
// prescribed directions, which must then be mutually orthogonal (e.g. two inclined symmetry
// planes at right angles).
void build_boundary(const Scene& scene, Model& m) {
  const std::string file = scene.file.string();
  const VolumeMesh& mesh = m.disc->mesh();
  const Eigen::Index n = mesh.num_vertices();
  m.dof_owner.assign(3 * n, -1);
  m.kinematics = std::make_shared<std::vector<KinematicCondition>>();
  struct Prescribed {
    Eigen::Vector3d direction;
    int condition;
  };
  std::vector<std::vector<Prescribed>> at(n);  // every prescribed direction of each vertex
  for (size_t i = 0; i < scene.boundary.size(); ++i) {
    const auto& b = scene.boundary[i];
    const std::string where = fmt::format("{}: /boundary/{}/select", file, i);
    KinematicCondition c{select_vertices(mesh, b.select, where), b.motion,
                         fmt::format("{}: /boundary/{}/motion", file, i), b.components, b.direction};
    // A direction along a coordinate axis is that component: no rotated frame needed.
    if (c.direction)
      for (int k = 0; k < 3; ++k)
        if (std::abs((*c.direction)(k)) == 1.0) {
          c.components = {k == 0, k == 1, k == 2};
          c.direction.reset();
        }
    if (static_cast<Eigen::Index>(c.vertices.size()) == n)
      m.warnings.push_back(fmt::format("{}: boundary condition '{}' selects every vertex of the body ({}); check its "
                                       "selector",
                                       where, b.name, n));
    const bool pinned = std::holds_alternative<Pinned>(b.motion);
    for (int v : c.vertices) {
      std::vector<Eigen::Vector3d> dirs;
      if (c.direction) dirs.push_back(*c.direction);
      for (int k = 0; k < 3; ++k)
        if (!c.direction && c.components[k]) dirs.push_back(Eigen::Vector3d::Unit(k));
      for (const Eigen::Vector3d& d : dirs) {
        for (const Prescribed& p : at[v]) {
          const double cosine = std::abs(p.direction.dot(d));
          if (cosine > 1.0 - 1e-12) {  // the same coordinate again
            if (pinned && std::holds_alternative<Pinned>(scene.boundary[p.condition].motion)) goto next_direction;
            throw Error(fmt::format("vertex {} is also prescribed along ({:g}, {:g}, {:g}) by /boundary/{} with a "
                                    "different motion",
                                    v, d(0), d(1), d(2), p.condition),
                        where);
          }
          if (cosine > 1e-9)
            throw Error(fmt::format("vertex {} is also prescribed by /boundary/{} along a direction at {:.4g} degrees to "
                                    "this one; directions prescribed at one vertex must be orthogonal",
                                    v, p.condition, std::acos(std::min(1.0, cosine)) * 180.0 / std::numbers::pi),
                        where);
        }
        at[v].push_back({d, static_cast<int>(i)});
      next_direction:;
      }
    }
    m.kinematics->push_back(std::move(c));
  }
  // Owners of global DOFs, and rotated frames where some direction is not an axis.
  std::vector<std::pair<int, Mat3>> frames;
  for (Eigen::Index v = 0; v < n; ++v) {
    const auto& dirs = at[v];
    const bool axes = std::all_of(dirs.begin(), dirs.end(), [](const Prescribed& p) {
      return (p.direction.array().abs() == 1.0).any();
    });
    if (axes) {
      for (const Prescribed& p : dirs) {
        Eigen::Index k = 0;
        p.direction.cwiseAbs().maxCoeff(&k);
        m.dof_owner[3 * v + k] = p.condition;
      }
      continue;
    }
    Mat3 Q = vertex_frame(dirs[0].direction);
    if (dirs.size() >= 2) {
      Q.col(1) = dirs[1].direction;
      Q.col(2) = dirs[0].direction.cross(dirs[1].direction).normalized();
    }
    frames.emplace_back(static_cast<int>(v), Q);
    m.vertex_frames.push_back({static_cast<int>(v), static_cast<int>(dirs.size())});
    for (const Prescribed& p : dirs) m.vertex_directions.push_back({static_cast<int>(v), p.condition, p.direction});
  }
  if (!frames.empty()) {
    if (scene.constraints)
      throw Error("a direction condition (roller on an inclined plane) is not available with energy-limited dynamics; "
                  "use components along the coordinate axes",
                  file + ": /boundary");
    m.problem->set_vertex_frames(frames);
  }
  const bool all_fixed = n > 0 && m.vertex_frames.empty() &&
                         std::all_of(m.dof_owner.begin(), m.dof_owner.end(), [](int o) { return o >= 0; });
  if (all_fixed)
    m.warnings.push_back(fmt::format("{}: /boundary: the boundary conditions prescribe every coordinate of every vertex: "
                                     "the body is fully pinned and nothing is solved",
                                     file));
}

// Marks the prescribed DOFs of rotated vertex frames (the first `count` local DOFs) in a fixed
// mask that apply_kinematics and the rig filled in global terms; a vertex a bone holds keeps all
// three fixed.
void mark_frame_dofs(const std::vector<VertexFrameDofs>& frames, std::vector<char>& fixed) {
  for (const auto& f : frames) {
    char* d = &fixed[3 * f.vertex];
    const bool held = d[0] && d[1] && d[2];
    for (int j = 0; j < 3; ++j) d[j] = held || j < f.count;
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
  apply_kinematics(*kinematics, rest, frame, x, fixed);
  rig.apply(frame, rest, x, fixed);
  mark_frame_dofs(vertex_frames, fixed);
}

std::vector<ScaledLoad> scene_loads(const Scene& scene, const Discretization& disc, const BoundarySurface& surface) {
  const std::string file = scene.file.string();
  const VolumeMesh& mesh = disc.mesh();
  std::vector<ScaledLoad> loads;
  if (scene.gravity.squaredNorm() > 0.0)
    loads.push_back({gravity_forces(lumped_mass(disc, scene.density), scene.gravity), scene.gravity_amplitude});
  if (scene.body_force.squaredNorm() > 0.0) loads.push_back({body_forces(disc, scene.body_force), scene.body_force_amplitude});
  for (size_t i = 0; i < scene.point_loads.size(); ++i) {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(disc.num_dofs());
    for (int v : select_vertices(mesh, scene.point_loads[i].select, fmt::format("{}: /loads/point/{}/select", file, i)))
      f.segment<3>(3 * v) += scene.point_loads[i].force;
    loads.push_back({std::move(f), scene.point_loads[i].amplitude});
  }
  for (size_t i = 0; i < scene.tractions.size(); ++i) {
    const std::string where = fmt::format("{}: /loads/traction/{}/select", file, i);
    loads.push_back({traction_forces(mesh, surface, select_vertices(mesh, scene.tractions[i].select, where),
                                     scene.tractions[i].traction, where),
                     scene.tractions[i].amplitude});
  }
  return loads;
}

Eigen::VectorXd loads_at(const std::vector<ScaledLoad>& loads, Eigen::Index num_dofs, double frame) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(num_dofs);
  for (const auto& l : loads) f += l.amplitude.at(frame) * l.forces;
  return f;
}

Eigen::VectorXd external_forces(const Scene& scene, const Discretization& disc, const BoundarySurface& surface) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(disc.num_dofs());
  for (const auto& l : scene_loads(scene, disc, surface)) f += l.forces;
  return f;
}

Eigen::VectorXd Model::external_forces_at(double frame) const { return loads_at(*loads, disc->num_dofs(), frame); }

Model build_model(const Scene& scene) {
  const std::string file = scene.file.string();
  Model m;
  m.disc = std::make_shared<Discretization>(build_scene_mesh(scene), file + ": /mesh");
  const VolumeMesh& mesh = m.disc->mesh();
  m.material = build_material_detailed(scene.material);
  build_elastic(scene, m);
  m.problem = std::make_shared<Problem>(mesh.num_vertices());
  m.problem->set_discretization(m.disc);  // for the linear solver's context (lattice, preconditioners)
  m.problem->add_form(m.elastic);
  m.surface = boundary_surface(mesh);
  m.problem->set_scales(problem_scales(mesh, m.material.lame));
  m.loads = std::make_shared<std::vector<ScaledLoad>>(scene_loads(scene, *m.disc, m.surface));
  m.external_forces = Eigen::VectorXd::Zero(m.disc->num_dofs());
  for (const auto& l : *m.loads) m.external_forces += l.forces;
  if (!m.loads->empty()) {
    m.load_form = std::make_shared<ExternalForceForm>(m.external_forces_at(1.0));
    m.problem->add_form(m.load_form);
  }
  build_pressures(scene, m);
  build_boundary(scene, m);
  m.rig = make_scene_rig(scene, mesh, *m.problem);  // bone springs and self-contact forms
  m.initial.x = mesh.rest_positions();
  // Everything that depends on the frame number: prescribed positions and the loads' amplitudes.
  // Captures copies (the model is returned by value); the conditions and loads are shared.
  PrescribedMotion motion = [kinematics = m.kinematics, rest = mesh.vertices, rig = m.rig, loads = m.loads,
                             load_form = m.load_form, frames = m.vertex_frames, pressures = m.pressures,
                             pressure_amplitudes = m.pressure_amplitudes](double frame, Eigen::VectorXd& x,
                                                                          std::vector<char>& fixed) {
    apply_kinematics(*kinematics, rest, frame, x, fixed);
    rig.apply(frame, rest, x, fixed);
    mark_frame_dofs(frames, fixed);
    if (load_form) load_form->forces() = loads_at(*loads, x.size(), frame);
    for (size_t i = 0; i < pressures.size(); ++i) pressures[i]->set_scale(pressure_amplitudes[i].at(frame));
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
  m.problem->set_matrix_free(scene.solver.linear.matrix_free);
  if (!scene.dynamics) {
    m.integrator = std::make_unique<QuasistaticIntegrator>(m.problem, std::move(motion), m.contact,
                                                           make_linear_solver(scene.solver.linear), scene.solver.newton,
                                                           scene.solver.predictor);
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
