#include "sinew/run/simulation.hpp"

#include <chrono>
#include <fmt/format.h>
#include <fstream>
#include <regex>
#include <sstream>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/model/model.hpp"
#include "sinew/run/checkpoint.hpp"
#include "sinew/run/frame_output.hpp"
#include "sinew/run/run_summary.hpp"

namespace sinew {

bool RunSummary::all_converged() const {
  for (const auto& f : frames)
    if (!f.converged) return false;
  return true;
}

std::string scene_fingerprint(const Scene& scene) {
  std::ifstream in(scene.file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return fmt::format("{:016x}", std::hash<std::string>{}(ss.str()));
}

// A fresh run replaces the files an earlier run left in the folder (only the names Sinew
// writes), so a shorter run does not leave stale frames behind.
void remove_previous_outputs(const std::filesystem::path& out) {
  static const std::regex ours(R"((frame_\d{4,}\.vtu|surface_\d{4,}\.obj|embedded_surface_\d{4,}\.(obj|ply)|embedded_surface\.pc2|embedded_surface_rest\.obj|(obstacle|bone)_.+_\d{4,}\.(vtu|obj)|viewer\.(html|glb)|simulation\.pvd|summary\.json|checkpoint\.json))");
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

using Clock = std::chrono::steady_clock;

// What is measured on a frame's final state: volume and J, support reactions, energies, contact.
void measure(const Model& model, const State& state, FrameRecord& record) {
  const Eigen::VectorXd& x = state.x;
  const Discretization& disc = *model.disc;
  const ElementFields fields = element_fields(model, x);
  record.volume = 0.0;
  for (Eigen::Index e = 0; e < disc.num_elements(); ++e) record.volume += fields.J(e) * disc.rest_volume(e);
  record.min_J = fields.J.minCoeff();
  // Support reactions: the unconstrained gradient of the total energy at a constrained vertex is
  // the force its boundary condition exerts there (body: -grad + support = 0).
  // Only the prescribed components count: a roller's reaction is normal to it.
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  for (const auto& form : model.problem->forms()) form->add_gradient(x, g);
  record.reactions.assign(model.kinematics.size(), Eigen::Vector3d::Zero());
  for (size_t i = 0; i < model.dof_owner.size(); ++i)
    if (const int c = model.dof_owner[i]; c >= 0) record.reactions[c](i % 3) += g(i);
  for (const auto& d : model.vertex_directions)
    record.reactions[d.condition] += d.direction * d.direction.dot(g.segment<3>(3 * d.vertex));
  const Eigen::VectorXd& loads = model.load_form ? model.load_form->forces() : model.external_forces;
  record.external_force = loads.reshaped(3, loads.size() / 3).rowwise().sum();
  record.potential_energy = model.elastic->value(x) - loads.dot(x);
  if (model.contact) {
    const ContactStats s = model.contact->stats(x);
    record.potential_energy += s.penalty_energy;
    record.contacts = s.contacts;
    record.max_penetration = s.max_penetration;
  }
  if (model.mass) {
    record.kinetic_energy = model.mass->kinetic_energy(state.v);
  } else if (model.integrator->dynamic()) {
    for (Eigen::Index i = 0; i < model.lumped_masses.size(); ++i)
      record.kinetic_energy += 0.5 * model.lumped_masses(i) * state.v.segment<3>(3 * i).squaredNorm();
  }
  if (model.rig.contact) {
    record.self_contacts = static_cast<int>(model.rig.contact->contacts().size());
    for (const SurfaceContact& c : model.rig.contact->detect(x)) record.self_penetration = std::max(record.self_penetration, c.depth);
  }
}

}  // namespace

RunSummary run_scene(const Scene& scene, const RunOptions& options) {
  const auto t_start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t_start).count(); };
  const int frames = options.frames.value_or(scene.frames);
  if (frames < 1) throw Error(fmt::format("must be at least 1, got {}", frames), "--frames");
  if (options.resume && options.out_dir.empty()) throw Error("resuming needs an output directory", "--resume");

  // ---- model: every input problem surfaces here, before a file is written
  Model model = build_model(scene);
  Integrator& integrator = *model.integrator;
  const Discretization& disc = *model.disc;
  const VolumeMesh& mesh = disc.mesh();
  RunSummary summary;
  summary.vertices = mesh.num_vertices();
  summary.elements = mesh.num_elements();
  for (Eigen::Index e = 0; e < disc.num_elements(); ++e) summary.rest_volume += disc.rest_volume(e);
  summary.external_force = model.external_forces.reshaped(3, model.external_forces.size() / 3).rowwise().sum();
  summary.warnings = model.warnings;
  if (options.strict && !model.warnings.empty()) throw Error(model.warnings.front() + " (a warning, an error with --strict)");
  if (options.warning)
    for (const auto& w : model.warnings) options.warning(w);
  State state = model.initial;
  int first_frame = 1;

  // ---- outputs and checkpoint
  const bool writing = !options.out_dir.empty();
  const std::filesystem::path& out = options.out_dir;
  const std::string fingerprint = scene_fingerprint(scene);
  FrameOutput output(scene, model, writing ? out : std::filesystem::path());
  if (options.resume) {
    Checkpoint c = read_checkpoint(out, fingerprint, integrator, state.x.size());
    state.x = std::move(c.state.x);
    if (integrator.dynamic()) state.v = std::move(c.state.v);
    try {
      integrator.restore_state(c.integrator_state, c.frame);
    } catch (const nlohmann::json::exception& e) {
      throw Error(fmt::format("corrupt checkpoint: {}", e.what()), (out / "checkpoint.json").string());
    }
    summary.frames = std::move(c.frames);
    output.set_pvd(std::move(c.pvd));
    first_frame = c.frame + 1;
  } else if (writing) {
    remove_previous_outputs(out);
  }
  if (writing) ensure_directory(out);
  auto frame_time = [&](int frame) { return integrator.dynamic() ? frame * integrator.frame_duration() : double(frame); };
  if (first_frame == 1) output.write(0, frame_time(0), state);

  // ---- one frame loop for every integrator
  for (int frame = first_frame; frame <= frames; ++frame) {
    const auto t_frame = Clock::now();
    if (options.progress) options.progress({frame, frames, 0, 0.0, elapsed(), false, nullptr});
    std::vector<double> residuals;
    auto progress = [&](int iteration, double residual) {
      residuals.push_back(residual);
      if (options.progress) options.progress({frame, frames, iteration, residual, elapsed(), false, nullptr});
    };
    FrameRecord record;
    static_cast<StepStats&>(record) = integrator.advance_frame(state, frame, progress);
    record.residuals = std::move(residuals);
    record.frame = frame;
    record.time = frame_time(frame);
    measure(model, state, record);
    record.seconds = std::chrono::duration<double>(Clock::now() - t_frame).count();
    summary.frames.push_back(record);
    output.write(frame, record.time, state);
    if (writing) {
      write_summary(out, scene, model, summary, frames);
      // Only after a converged frame, so --resume never continues from a failed state.
      if (record.converged)
        write_checkpoint(out, fingerprint, integrator,
                         {frame, state, integrator.checkpoint_state(), summary.frames, output.pvd()});
    }
    if (options.progress) options.progress({frame, frames, record.newton_iterations, record.residual, elapsed(), true, &summary.frames.back()});
    if (!record.converged) break;  // later frames would start from an unsolved state
  }
  summary.x = state.x;
  return summary;
}

}  // namespace sinew
