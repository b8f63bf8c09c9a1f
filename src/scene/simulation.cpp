#include "sinew/scene/simulation.hpp"

#include <chrono>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "sinew/core/error.hpp"
#include "sinew/fem/elastic_form.hpp"
#include "sinew/fem/external_force_form.hpp"
#include "sinew/fem/mass.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/io/obj_writer.hpp"
#include "sinew/io/vtk_writer.hpp"
#include "sinew/scene/scene_surface.hpp"
#include "sinew/mesh/surface.hpp"
#include "sinew/scene/constrained_simulation.hpp"
#include "sinew/scene/dynamic_model.hpp"
#include "sinew/scene/scene_rig.hpp"
#include "sinew/scene/shape_output.hpp"
#include "sinew/solver/newton.hpp"

namespace sinew {

bool RunSummary::all_converged() const {
  for (const auto& f : frames)
    if (!f.converged) return false;
  return true;
}

namespace {

using Clock = std::chrono::steady_clock;

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

nlohmann::json vec_json(const Eigen::Vector3d& v) { return {v(0), v(1), v(2)}; }

nlohmann::json reactions_json(const std::vector<Eigen::Vector3d>& forces) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& f : forces) j.push_back(vec_json(f));
  return j;
}

nlohmann::json to_json(const FrameRecord& r) {
  return {{"frame", r.frame},
          {"converged", r.converged},
          {"newton_iterations", r.newton_iterations},
          {"linear_iterations", r.linear_iterations},
          {"substeps", r.substeps},
          {"residual", r.residual},
          {"energy", r.energy},
          {"volume", r.volume},
          {"min_J", r.min_J},
          {"reactions", reactions_json(r.reactions)},
          {"kinetic_energy", r.kinetic_energy},
          {"potential_energy", r.potential_energy},
          {"contacts", r.contacts},
          {"max_penetration", r.max_penetration},
          {"self_contacts", r.self_contacts},
          {"self_penetration", r.self_penetration},
          {"seconds", r.seconds},
          {"assembly_seconds", r.assembly_seconds},
          {"solve_seconds", r.solve_seconds},
          {"failure", r.failure}};
}

FrameRecord frame_from_json(const nlohmann::json& j) {
  FrameRecord r;
  r.frame = j.at("frame");
  r.converged = j.at("converged");
  r.newton_iterations = j.at("newton_iterations");
  r.linear_iterations = j.at("linear_iterations");
  r.substeps = j.at("substeps");
  r.residual = j.at("residual");
  r.energy = j.at("energy");
  r.volume = j.at("volume");
  r.min_J = j.at("min_J");
  for (const auto& f : j.at("reactions")) r.reactions.emplace_back(f.at(0), f.at(1), f.at(2));
  r.kinetic_energy = j.value("kinetic_energy", 0.0);
  r.potential_energy = j.value("potential_energy", 0.0);
  r.contacts = j.value("contacts", 0);
  r.max_penetration = j.value("max_penetration", 0.0);
  r.self_contacts = j.value("self_contacts", 0);
  r.self_penetration = j.value("self_penetration", 0.0);
  r.seconds = j.at("seconds");
  r.assembly_seconds = j.at("assembly_seconds");
  r.solve_seconds = j.at("solve_seconds");
  r.failure = j.at("failure");
  return r;
}

// What a checkpoint restores.
struct Checkpoint {
  int frame = 0;
  Eigen::VectorXd x;
  Eigen::VectorXd v;  // dynamics only
  std::vector<FrameRecord> frames;
  std::vector<std::pair<double, std::string>> pvd;
};

Checkpoint read_checkpoint(const std::filesystem::path& out, const std::string& fingerprint, Eigen::Index dofs) {
  const auto cp = out / "checkpoint.json";
  std::ifstream in(cp);
  if (!in) throw Error("no checkpoint to resume from (run without --resume first)", cp.string());
  Checkpoint c;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.at("scene_fingerprint") != fingerprint)
      throw Error("the scene file changed since the checkpoint was written; run again without --resume", cp.string());
    const auto& xs = j.at("x");
    if (static_cast<Eigen::Index>(xs.size()) != dofs)
      throw Error("checkpoint belongs to a different mesh (state has the wrong size)", cp.string());
    c.x.resize(dofs);
    for (Eigen::Index i = 0; i < dofs; ++i) c.x(i) = xs[static_cast<size_t>(i)].get<double>();
    if (!c.x.allFinite()) throw Error("checkpoint state is not finite", cp.string());
    if (j.contains("v")) {  // dynamics
      const auto v = j.at("v").get<std::vector<double>>();
      if (static_cast<Eigen::Index>(v.size()) != dofs) throw Error("checkpoint velocities have the wrong size", cp.string());
      c.v = Eigen::Map<const Eigen::VectorXd>(v.data(), dofs);
      if (!c.v.allFinite()) throw Error("checkpoint velocities are not finite", cp.string());
    }
    for (const auto& f : j.at("frames")) c.frames.push_back(frame_from_json(f));
    for (const auto& p : j.at("pvd")) c.pvd.emplace_back(p.at(0).get<double>(), p.at(1).get<std::string>());
    c.frame = j.at("frame").get<int>();
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("corrupt checkpoint: {}", e.what()), cp.string());
  }
  return c;
}

}  // namespace

std::string scene_fingerprint(const Scene& scene) {
  std::ifstream in(scene.file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return fmt::format("{:016x}", std::hash<std::string>{}(ss.str()));
}

// A fresh run replaces the files an earlier run left in the folder (only the names Sinew
// writes), so a shorter run does not leave stale frames behind.
void remove_previous_outputs(const std::filesystem::path& out) {
  static const std::regex ours(R"((frame_\d{4,}\.vtu|surface_\d{4,}\.obj|embedded_surface_\d{4,}\.(obj|ply)|embedded_surface\.pc2|embedded_surface_rest\.obj|(obstacle|bone)_.+_\d{4,}\.(vtu|obj)|simulation\.pvd|summary\.json|checkpoint\.json))");
  std::error_code ec;
  if (!std::filesystem::is_directory(out, ec)) return;
  for (const auto& entry : std::filesystem::directory_iterator(out)) {
    if (entry.is_regular_file() && std::regex_match(entry.path().filename().string(), ours)) {
      std::filesystem::remove(entry.path(), ec);
      if (ec) throw Error(fmt::format("cannot remove an earlier run's file: {}", ec.message()), entry.path().string());
    }
  }
}

namespace {

// Everything the load steps need, built and validated before anything is written.
struct Model {
  std::shared_ptr<Discretization> disc;
  BuiltMaterial material;
  std::shared_ptr<ElasticForm> elastic;
  std::unique_ptr<Problem> problem;
  BoundarySurface surface;
  Eigen::VectorXd forces;  // constant external nodal forces
  std::vector<KinematicCondition> kinematics;
  std::vector<int> boundary_owner;  // per vertex: the first boundary entry selecting it, or -1
  DynamicModel dynamic;  // obstacles and dynamics (dynamic_model.hpp)
  SceneRig rig;                     // bones and self-contact
};

Model build_model(const Scene& scene) {
  const std::string file = scene.file.string();
  Model m;
  m.disc = std::make_shared<Discretization>(build_scene_mesh(scene), file + ": /mesh");
  const VolumeMesh& mesh = m.disc->mesh();
  m.material = build_material_detailed(scene.material);
  m.elastic = std::make_shared<ElasticForm>(m.disc, m.material.material, scene.solver.projection);
  m.problem = std::make_unique<Problem>(mesh.num_vertices());
  m.problem->add_form(m.elastic);
  m.surface = boundary_surface(mesh);

  m.forces = external_forces(scene, *m.disc, m.surface);
  if (m.forces.squaredNorm() > 0.0) m.problem->add_form(std::make_shared<ExternalForceForm>(m.forces));

  // A vertex moved by two different boundary motions has no well-defined position.
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
  m.dynamic = build_dynamic_model(scene, m.disc, m.elastic, m.surface, *m.problem, m.kinematics);
  m.rig = make_scene_rig(scene, mesh, *m.problem);
  // Bones drive their vertices at every time step's end, like the boundary motions.
  if (m.dynamic.dynamic() && m.rig.rig)
    m.dynamic.stepper->add_kinematic_hook([rig = m.rig](double frame, const Eigen::MatrixX3d& rest, Eigen::VectorXd& x,
                                                         std::vector<char>& fixed) { rig.apply(frame, rest, x, fixed); });
  return m;
}

Eigen::Vector3d total_force(const Eigen::VectorXd& f) {
  return f.reshaped(3, f.size() / 3).rowwise().sum();
}

}  // namespace

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

RunSummary run_scene(const Scene& scene, const RunOptions& options) {
  if (scene.constraints) return run_constrained_scene(scene, options);  // paper 001 dynamics
  const auto t_start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t_start).count(); };
  const int frames = options.frames.value_or(scene.frames);
  if (frames < 1) throw Error(fmt::format("must be at least 1, got {}", frames), "--frames");
  if (options.resume && options.out_dir.empty()) throw Error("resuming needs an output directory", "--resume");

  // ---- model: every input problem surfaces here, before a file is written
  Model model = build_model(scene);
  const Discretization& disc = *model.disc;
  const VolumeMesh& mesh = disc.mesh();
  Problem& problem = *model.problem;
  auto linear = make_linear_solver(scene.solver.linear);
  EmbeddedSurfaceOutput embedded(scene, mesh);  // embedded_surface_output.hpp
  const ShapeOutput shapes(scene, mesh);         // obstacles and bones, shape_output.hpp
  // ParaView time: seconds in dynamics, the frame number in quasistatics (stated in the .pvd).
  const double seconds_per_frame = model.dynamic.dynamic() ? scene.dynamics->time_step : 1.0;
  const PvdTime pvd_time = model.dynamic.dynamic() ? PvdTime::Seconds : PvdTime::Frames;

  RunSummary summary;
  summary.vertices = mesh.num_vertices();
  summary.elements = mesh.num_elements();
  for (Eigen::Index e = 0; e < disc.num_elements(); ++e) summary.rest_volume += disc.rest_volume(e);
  summary.external_force = total_force(model.forces);
  Eigen::VectorXd x = mesh.rest_positions();
  int first_frame = 1;

  // ---- outputs and checkpoint
  const bool writing = !options.out_dir.empty();
  const std::filesystem::path& out = options.out_dir;
  const std::string fingerprint = scene_fingerprint(scene);
  std::vector<std::pair<double, std::string>> pvd_entries;
  if (options.resume) {
    Checkpoint c = read_checkpoint(out, fingerprint, x.size());
    x = std::move(c.x);
    if (model.dynamic.dynamic()) {
      if (c.v.size() != x.size()) throw Error("checkpoint has no velocities (written by a quasistatic run)", (out / "checkpoint.json").string());
      model.dynamic.v = std::move(c.v);
    }
    summary.frames = std::move(c.frames);
    pvd_entries = std::move(c.pvd);
    first_frame = c.frame + 1;
  } else if (writing) {
    remove_previous_outputs(out);
  }
  if (writing) ensure_directory(out);

  auto write_frame = [&](int frame) {
    if (!writing || frame % scene.output.every != 0) return;
    std::optional<ElasticForm::ElementFields> fields;
    if (scene.output.vtu || embedded.active()) fields = model.elastic->element_fields(x);
    if (scene.output.vtu) {
      VtuFields vf;
      vf.cell_scalars = {{"J", fields->J}, {"energy_density", fields->energy_density},
                         {"stress_norm", fields->stress_norm}, {"energy", fields->energy}};
      const std::string name = fmt::format("frame_{:04d}.vtu", frame);
      write_vtu(out / name, mesh, x, vf);
      std::erase_if(pvd_entries, [&](const auto& e) { return e.second == name; });
      pvd_entries.emplace_back(frame * seconds_per_frame, name);
      write_pvd(out / "simulation.pvd", pvd_entries, pvd_time);
    }
    if (scene.output.obj) write_surface_obj(out / fmt::format("surface_{:04d}.obj", frame), mesh, model.surface, x);
    if (embedded.active()) embedded.write(out, frame, x, disc, &fields->J, &fields->stress_norm);
    shapes.write(out, frame);
  };

  auto frames_json = [&] {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& r : summary.frames) j.push_back(to_json(r));
    return j;
  };
  nlohmann::json boundary_names = nlohmann::json::array();
  for (const auto& b : scene.boundary) boundary_names.push_back(b.name);
  auto write_summary = [&] {
    if (!writing) return;
    int newton = 0, linear_its = 0;
    for (const auto& r : summary.frames) newton += r.newton_iterations, linear_its += r.linear_iterations;
    const nlohmann::json s = {{"scene", scene.file.string()},
                              {"description", scene.description},
                              {"vertices", summary.vertices},
                              {"elements", summary.elements},
                              {"element", to_string(mesh.kind)},
                              {"material", model.material.material->name()},
                              {"lame", {{"lambda", model.material.lame.lambda}, {"mu", model.material.lame.mu}}},
                              {"density", scene.density},
                              {"rest_volume", summary.rest_volume},
                              {"external_force", vec_json(summary.external_force)},
                              {"boundary", boundary_names},
                              {"frames_requested", frames},
                              {"frames_completed", static_cast<int>(summary.frames.size())},
                              {"total_newton_iterations", newton},
                              {"total_linear_iterations", linear_its},
                              {"all_converged", summary.all_converged()},
                              {"frames", frames_json()}};
    write_file_atomically(out / "summary.json", [&](std::ostream& os) { os << s.dump(2) << '\n'; });
  };
  // Written only after a converged frame, so --resume never continues from a failed state.
  auto write_checkpoint = [&](int frame) {
    if (!writing) return;
    nlohmann::json cp = {{"scene_fingerprint", fingerprint}, {"frame", frame}, {"vertices", summary.vertices},
                         {"frames", frames_json()}, {"pvd", pvd_entries}};
    cp["x"] = std::vector<double>(x.data(), x.data() + x.size());
    const Eigen::VectorXd& v = model.dynamic.v;
    if (model.dynamic.dynamic()) cp["v"] = std::vector<double>(v.data(), v.data() + v.size());
    write_file_atomically(out / "checkpoint.json", [&](std::ostream& os) { os << cp.dump() << '\n'; });
  };

  if (first_frame == 1) write_frame(0);

  // ---- load stepping
  for (int frame = first_frame; frame <= frames; ++frame) {
    const auto t_frame = Clock::now();
    FrameRecord record;
    record.frame = frame;
    if (options.progress) options.progress({frame, frames, 0, 0.0, elapsed(), false, nullptr});
    auto newton_progress = [&](const NewtonIterate& it) {
      if (options.progress) options.progress({frame, frames, it.iteration, it.residual, elapsed(), false, nullptr});
    };
    // Solve at the frame's boundary positions. If the jump is too large (an invalid start or
    // no convergence), halve the step from the last solved state, down to 1/2^kMaxMotionSplits
    // of the frame's motion, and lengthen it again after each success.
    const double min_step = 1.0 / (1 << kMaxMotionSplits);
    double solved = frame - 1.0, step = 1.0;
    record.substeps = 0;
    if (model.dynamic.dynamic()) {
      advance_dynamic_frame(model.dynamic, scene, x, frame, *linear, record, newton_progress);
      solved = frame;  // time steps are never split
    }
    while (solved < frame) {
      const double target = std::min<double>(frame, solved + step);
      Eigen::VectorXd trial = x;
      std::vector<char> fixed(trial.size(), 0);
      apply_kinematics(model.kinematics, mesh.vertices, target, trial, fixed);
      model.rig.apply(target, mesh.vertices, trial, fixed);
      problem.set_fixed(fixed);
      if (model.dynamic.contact) model.dynamic.contact->begin_step(x, solved, target, 0.0);  // obstacles at `target`
      const NewtonReport r = newton_solve(problem, trial, *linear, scene.solver.newton, newton_progress);
      record.newton_iterations += r.iterations;
      record.linear_iterations += r.linear_iterations;
      record.assembly_seconds += r.assembly_seconds;
      record.solve_seconds += r.solve_seconds;
      record.residual = r.residual;
      record.energy = r.energy;
      if (r.converged) {
        x = trial;
        solved = target;
        record.substeps += 1;
        step = std::min(1.0, 2.0 * step);
      } else if (step > min_step) {
        step *= 0.5;
      } else {
        x = trial;  // kept for inspection (written below), never continued from
        record.failure = fmt::format("{} (even with the frame's motion split into steps of 1/{})", r.failure,
                                     1 << kMaxMotionSplits);
        break;
      }
    }
    record.converged = record.failure.empty();
    const auto fields = model.elastic->element_fields(x);
    record.volume = 0.0;
    for (Eigen::Index e = 0; e < disc.num_elements(); ++e) record.volume += fields.J(e) * disc.rest_volume(e);
    record.min_J = fields.J.minCoeff();
    // Support reactions: the unconstrained gradient of the total potential at a constrained
    // vertex is the force its boundary condition exerts there (body: -grad + support = 0).
    Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
    for (const auto& form : problem.forms()) form->add_gradient(x, g);
    record.reactions.assign(model.kinematics.size(), Eigen::Vector3d::Zero());
    for (size_t v = 0; v < model.boundary_owner.size(); ++v)
      if (model.boundary_owner[v] >= 0) record.reactions[model.boundary_owner[v]] += g.segment<3>(3 * v);
    record_energies(model.dynamic, *model.elastic, model.forces, x, record);
    if (model.rig.contact) {
      record.self_contacts = static_cast<int>(model.rig.contact->contacts().size());
      for (const SurfaceContact& c : model.rig.contact->detect(x)) record.self_penetration = std::max(record.self_penetration, c.depth);
    }
    record.seconds = std::chrono::duration<double>(Clock::now() - t_frame).count();
    summary.frames.push_back(record);
    write_frame(frame);
    write_summary();
    if (record.converged) write_checkpoint(frame);
    if (options.progress) options.progress({frame, frames, record.newton_iterations, record.residual, elapsed(), true, &summary.frames.back()});
    if (!record.converged) break;  // later frames would start from an unsolved state
  }
  summary.x = x;
  return summary;
}

}  // namespace sinew
