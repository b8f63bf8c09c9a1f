#include "sinew/scene/constrained_simulation.hpp"

#include <chrono>
#include <fstream>
#include <map>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "sinew/constraints/corotational_hex.hpp"
#include "sinew/constraints/hyperelastic_energy_model.hpp"
#include "sinew/constraints/obstacle_contacts.hpp"
#include "sinew/core/error.hpp"
#include "sinew/fem/mass.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/io/obj_writer.hpp"
#include "sinew/io/vtk_writer.hpp"
#include "sinew/scene/shape_output.hpp"
#include "sinew/scene/simulation.hpp"
#include "sinew/mesh/surface.hpp"

namespace sinew {
namespace {

using Clock = std::chrono::steady_clock;

// What one frame (steps_per_frame steps) did, for summary.json.
struct ConstrainedFrame : ConstrainedStepTotals {
  double elastic_energy = 0.0, kinetic_energy = 0.0;
};

nlohmann::json frame_json(const FrameRecord& r, const ConstrainedFrame& c, double time) {
  return {{"frame", r.frame},
          {"time", time},
          {"converged", r.converged},
          {"steps", c.steps},
          {"sqp_iterations", c.sqp_iterations},
          {"max_sqp_iterations_per_step", c.max_sqp_iterations},
          {"pgs_iterations", c.pgs_iterations},
          {"max_pgs_residual", c.max_pgs_residual},
          {"factorizations", c.factorizations},
          {"cg_iterations", c.cg_iterations},
          {"splitting_iterations", c.splitting_iterations},
          {"max_energy_violation", c.max_energy_violation},
          {"max_penetration", c.max_penetration},
          {"max_active_energy_constraints", c.max_active_energy},
          {"max_active_contacts", c.max_active_contacts},
          {"max_element_energy", c.max_element_energy},
          {"elastic_energy", c.elastic_energy},
          {"kinetic_energy", c.kinetic_energy},
          {"volume", r.volume},
          {"seconds", r.seconds},
          {"failure", r.failure}};
}

// The FrameRecord (what the CLI and RunSummary report) of a frame's summary.json entry.
FrameRecord frame_record_from_json(const nlohmann::json& j) {
  FrameRecord r;
  r.frame = j.at("frame");
  r.converged = j.at("converged");
  r.newton_iterations = j.at("sqp_iterations");
  r.linear_iterations = j.at("pgs_iterations");
  r.residual = std::max(j.at("max_energy_violation").get<double>(), j.at("max_penetration").get<double>());
  r.energy = j.at("elastic_energy");
  r.kinetic_energy = j.at("kinetic_energy");
  r.volume = j.at("volume");
  r.seconds = j.at("seconds");
  r.solve_seconds = r.seconds;
  r.failure = j.at("failure");
  return r;
}

// What a constrained run's checkpoint restores: the state after the last converged frame, the
// stepper's multipliers (its warm start) and the frames so far. The lagged factorisations are
// not stored: the resumed run refactorises at its first step, so it agrees with an
// uninterrupted run to the solver tolerances (CG, LCP), not bit for bit.
struct ConstrainedCheckpoint {
  int frame = 0;
  Eigen::VectorXd x, v;
  std::map<long, double> multipliers;
  nlohmann::json frames = nlohmann::json::array();
  std::vector<std::pair<double, std::string>> pvd;
};

ConstrainedCheckpoint read_constrained_checkpoint(const std::filesystem::path& out, const std::string& fingerprint,
                                                  Eigen::Index dofs) {
  const std::string cp = (out / "checkpoint.json").string();
  std::ifstream in(cp);
  if (!in) throw Error("no checkpoint to resume from (run without --resume first)", cp);
  ConstrainedCheckpoint c;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.value("mode", "") != "constrained")
      throw Error("checkpoint was not written by a constrained (paper 001) run; run again without --resume", cp);
    if (j.at("scene_fingerprint") != fingerprint)
      throw Error("the scene file changed since the checkpoint was written; run again without --resume", cp);
    for (const char* key : {"x", "v"}) {
      const auto values = j.at(key).get<std::vector<double>>();
      if (static_cast<Eigen::Index>(values.size()) != dofs)
        throw Error(fmt::format("checkpoint {} has the wrong size (another mesh?)", key), cp);
      Eigen::VectorXd& target = std::string(key) == "x" ? c.x : c.v;
      target = Eigen::Map<const Eigen::VectorXd>(values.data(), dofs);
      if (!target.allFinite()) throw Error(fmt::format("checkpoint {} is not finite", key), cp);
    }
    for (const auto& m : j.at("multipliers")) c.multipliers[m.at(0).get<long>()] = m.at(1).get<double>();
    c.frames = j.at("frames");
    for (const auto& p : j.at("pvd")) c.pvd.emplace_back(p.at(0).get<double>(), p.at(1).get<std::string>());
    c.frame = j.at("frame").get<int>();
  } catch (const nlohmann::json::exception& e) {
    throw Error(fmt::format("corrupt checkpoint: {}", e.what()), cp);
  }
  return c;
}

}  // namespace

RunSummary run_constrained_scene(const Scene& scene, const RunOptions& options) {
  const auto t_start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t_start).count(); };
  const ConstraintsSpec& spec = *scene.constraints;
  const DynamicsSpec& dynamics = *scene.dynamics;  // the scene reader requires it with `constraints`
  const int steps_per_frame = dynamics.substeps;
  const std::string file = scene.file.string();
  const int frames = options.frames.value_or(scene.frames);
  if (frames < 1) throw Error(fmt::format("must be at least 1, got {}", frames), "--frames");
  if (options.resume && options.out_dir.empty()) throw Error("resuming needs an output directory", "--resume");
  // Bones and self-contact drive the incremental-potential solver only; refuse rather than ignore.
  if (scene.rig) throw Error("bones are not supported with a constraints section", file + ": /rig");
  if (scene.self_contact) throw Error("self-contact is not supported with a constraints section", file + ": /self_contact");

  // ---- model, validated before anything is written
  auto disc = std::make_shared<Discretization>(build_scene_mesh(scene), file + ": /mesh");
  const VolumeMesh& mesh = disc->mesh();
  const BuiltMaterial material = build_material_detailed(scene.material);
  std::shared_ptr<const ElementEnergyModel> model;
  if (spec.model == "corotational") {
    if (mesh.kind != ElementKind::Hex8)
      throw Error("the corotational model needs hexahedra (mesh element \"hex\")", file + ": /constraints/model");
    // Hookean coefficients from the material's small-strain Lame parameters: E1 = lambda + 2 mu,
    // E2 = lambda, E3 = mu (paper 001 §4.2).
    const double lambda = material.lame.lambda, mu = material.lame.mu;
    model = std::make_shared<CorotationalHex>(disc, HookeCoefficients{lambda + 2 * mu, lambda, mu});
  } else {
    model = std::make_shared<HyperelasticEnergyModel>(disc, material.material);
  }
  const BoundarySurface surface = boundary_surface(mesh);
  const Eigen::VectorXd masses = lumped_mass(*disc, scene.density);
  const Eigen::VectorXd forces = external_forces(scene, *disc, surface);
  std::vector<char> fixed(disc->num_dofs(), 0);
  for (size_t i = 0; i < scene.boundary.size(); ++i) {
    const std::string where = fmt::format("{}: /boundary/{}", file, i);
    if (!std::holds_alternative<Pinned>(scene.boundary[i].motion))
      throw Error("only pinned boundaries are supported with a constraints section", where + "/motion");
    for (int v : select_vertices(mesh.vertices, scene.boundary[i].select, where + "/select"))
      fixed[3 * v] = fixed[3 * v + 1] = fixed[3 * v + 2] = 1;
  }
  ContactProvider contacts;
  if (!scene.obstacles.empty()) {
    std::vector<ObstacleContact> obstacles;
    for (const ObstacleSpec& o : scene.obstacles)
      obstacles.push_back({std::make_shared<Obstacle>(o.name, o.shape, o.motion), o.contact.friction});
    contacts = obstacle_contacts(std::move(obstacles), surface.vertices, spec.contact_margin, dynamics.time_step);
  }
  ConstrainedStepper stepper(model, masses, forces, fixed, contacts, spec.step);

  RunSummary summary;
  summary.vertices = mesh.num_vertices();
  summary.elements = mesh.num_elements();
  for (Eigen::Index e = 0; e < disc->num_elements(); ++e) summary.rest_volume += disc->rest_volume(e);
  summary.external_force = forces.reshaped(3, forces.size() / 3).rowwise().sum();
  Eigen::VectorXd x = mesh.rest_positions(), v = Eigen::VectorXd::Zero(x.size());
  for (Eigen::Index i = 0; i < mesh.num_vertices(); ++i)
    if (!fixed[3 * i]) v.segment<3>(3 * i) = dynamics.initial_velocity;

  // ---- outputs and checkpoint
  const bool writing = !options.out_dir.empty();
  const auto& out = options.out_dir;
  const std::string fingerprint = scene_fingerprint(scene);
  const double h = spec.step.time_step;
  std::vector<std::pair<double, std::string>> pvd;
  nlohmann::json frames_json = nlohmann::json::array();
  int first_frame = 1;
  if (options.resume) {
    ConstrainedCheckpoint c = read_constrained_checkpoint(out, fingerprint, x.size());
    x = std::move(c.x);
    v = std::move(c.v);
    stepper.set_multipliers(std::move(c.multipliers));
    stepper.set_time(c.frame * steps_per_frame * h);
    for (const auto& f : c.frames) summary.frames.push_back(frame_record_from_json(f));
    frames_json = std::move(c.frames);
    pvd = std::move(c.pvd);
    first_frame = c.frame + 1;
  } else if (writing) {
    remove_previous_outputs(out);
    ensure_directory(out);
  }
  auto element_energies = [&] {
    Eigen::VectorXd U(disc->num_elements());
    for (Eigen::Index e = 0; e < U.size(); ++e) U(e) = model->element_energy(e, x);
    return U;
  };
  const ShapeOutput shapes(scene, mesh);
  auto write_frame = [&](int frame) {
    if (!writing || frame % scene.output.every != 0) return;
    if (scene.output.vtu) {
      VtuFields fields;
      fields.cell_scalars = {{"energy", element_energies()}};
      if (spec.step.energy_limit) fields.cell_scalars.push_back({"energy_ratio", element_energies() / spec.step.energy_limit->max_energy});
      fields.point_vectors = {{"velocity", v}};
      const std::string name = fmt::format("frame_{:04d}.vtu", frame);
      write_vtu(out / name, mesh, x, fields);
      pvd.emplace_back(frame * steps_per_frame * h, name);
      write_pvd(out / "simulation.pvd", pvd, PvdTime::Seconds);
    }
    if (scene.output.obj) write_surface_obj(out / fmt::format("surface_{:04d}.obj", frame), mesh, surface, x);
    shapes.write(out, frame);  // obstacles, shape_output.hpp
  };
  auto write_summary = [&] {
    if (!writing) return;
    int sqp = 0, pgs = 0;
    for (const auto& f : frames_json) sqp += f["sqp_iterations"].get<int>(), pgs += f["pgs_iterations"].get<int>();
    nlohmann::json s = {{"scene", file},
                        {"description", scene.description},
                        {"mode", "constrained dynamics (paper 001)"},
                        {"model", model->name()},
                        {"vertices", summary.vertices},
                        {"elements", summary.elements},
                        {"element", to_string(mesh.kind)},
                        {"material", material.material->name()},
                        {"lame", {{"lambda", material.lame.lambda}, {"mu", material.lame.mu}}},
                        {"density", scene.density},
                        {"rest_volume", summary.rest_volume},
                        {"time_step", h},
                        {"steps_per_frame", steps_per_frame},
                        {"energy_limit", spec.step.energy_limit ? nlohmann::json(spec.step.energy_limit->max_energy) : nlohmann::json()},
                        {"jacobian", spec.step.energy_limit ? to_string(spec.step.energy_limit->jacobian) : "none"},
                        {"frames_requested", frames},
                        {"frames_completed", static_cast<int>(summary.frames.size())},
                        {"total_sqp_iterations", sqp},
                        {"total_pgs_iterations", pgs},
                        {"all_converged", summary.all_converged()},
                        {"frames", frames_json}};
    write_file_atomically(out / "summary.json", [&](std::ostream& os) { os << s.dump(2) << '\n'; });
  };
  // Written only after a converged frame, so --resume never continues from a failed state.
  auto write_checkpoint = [&](int frame) {
    if (!writing) return;
    nlohmann::json multipliers = nlohmann::json::array();
    for (const auto& [key, value] : stepper.multipliers()) multipliers.push_back({key, value});
    nlohmann::json cp = {{"mode", "constrained"}, {"scene_fingerprint", fingerprint}, {"frame", frame},
                         {"multipliers", multipliers},  {"frames", frames_json}, {"pvd", pvd}};
    cp["x"] = std::vector<double>(x.data(), x.data() + x.size());
    cp["v"] = std::vector<double>(v.data(), v.data() + v.size());
    write_file_atomically(out / "checkpoint.json", [&](std::ostream& os) { os << cp.dump() << '\n'; });
  };
  if (first_frame == 1) write_frame(0);

  // ---- time stepping
  for (int frame = first_frame; frame <= frames; ++frame) {
    const auto t_frame = Clock::now();
    if (options.progress) options.progress({frame, frames, 0, 0.0, elapsed(), false, nullptr});
    FrameRecord record;
    record.frame = frame;
    ConstrainedFrame cf;
    for (int s = 0; s < steps_per_frame; ++s) {
      const ConstrainedStepReport r = stepper.step(x, v);
      cf.add(r);
      if (!r.converged && record.failure.empty())
        record.failure = fmt::format(
            "step {} of the frame: SQP stopped after {} iteration(s) with energy violation {:.3e} (tolerance {:.1e}), "
            "penetration {:.3e} m (tolerance {:.1e}), PGS residual {:.3e} (tolerance {:.1e})",
            s + 1, r.sqp_iterations, r.energy_violation, spec.step.energy_tolerance, r.penetration,
            spec.step.contact_tolerance, r.pgs_residual, spec.step.pgs.tolerance);
    }
    record.converged = record.failure.empty();
    record.newton_iterations = cf.sqp_iterations;
    record.linear_iterations = cf.pgs_iterations;
    record.residual = std::max(cf.max_energy_violation, cf.max_penetration);
    const Eigen::VectorXd U = element_energies();
    cf.elastic_energy = U.sum();
    for (Eigen::Index i = 0; i < mesh.num_vertices(); ++i) cf.kinetic_energy += 0.5 * masses(i) * v.segment<3>(3 * i).squaredNorm();
    record.energy = cf.elastic_energy;
    record.volume = 0.0;
    for (Eigen::Index e = 0; e < disc->num_elements(); ++e) {
      const Eigen::Matrix3Xd xe = disc->element_positions(e, x);
      for (int q = 0; q < disc->quadrature_points(); ++q) record.volume += disc->weight(e, q) * (xe * disc->gradients(e, q)).determinant();
    }
    record.seconds = std::chrono::duration<double>(Clock::now() - t_frame).count();
    record.solve_seconds = record.seconds;
    summary.frames.push_back(record);
    frames_json.push_back(frame_json(record, cf, frame * steps_per_frame * h));
    write_frame(frame);
    write_summary();
    if (record.converged) write_checkpoint(frame);
    if (options.progress) options.progress({frame, frames, record.newton_iterations, record.residual, elapsed(), true, &summary.frames.back()});
    if (!record.converged) break;  // reported, and the state written for inspection
  }
  summary.x = x;
  return summary;
}

}  // namespace sinew
