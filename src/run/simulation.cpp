#include "sinew/run/simulation.hpp"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <regex>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/io/deferred_sync.hpp"
#include "sinew/io/folder_lock.hpp"
#include "sinew/model/model.hpp"
#include "sinew/run/checkpoint.hpp"
#include "sinew/run/checkpoint_schedule.hpp"
#include "sinew/run/frame_log.hpp"
#include "sinew/run/frame_output.hpp"
#include "sinew/run/run_summary.hpp"
#include "sinew/run/selection_output.hpp"

namespace sinew {

bool RunSummary::all_converged() const {
  for (const auto& f : frames)
    if (!f.converged) return false;
  return true;
}

// A fresh run replaces the files an earlier run left in the folder (only the names Sinew
// writes), so a shorter run does not leave stale frames behind.
void remove_previous_outputs(const std::filesystem::path& out) {
  static const std::regex ours(R"((frame_\d{4,}\.vtu|surface_\d{4,}\.obj|embedded_surface_\d{4,}\.(obj|ply)|embedded_surface\.pc2|embedded_surface_rest\.obj|(obstacle|bone)_.+_\d{4,}\.(vtu|obj)|viewer\.(html|glb)|simulation\.pvd|summary\.json|frames\.jsonl|checkpoint\.json|selections\.json))");
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
  record.reactions.assign(model.kinematics->size(), Eigen::Vector3d::Zero());
  for (size_t i = 0; i < model.dof_owner.size(); ++i)
    if (const int c = model.dof_owner[i]; c >= 0) record.reactions[c](i % 3) += g(i);
  for (const auto& d : model.vertex_directions)
    record.reactions[d.condition] += d.direction * d.direction.dot(g.segment<3>(3 * d.vertex));
  const Eigen::VectorXd& loads = model.load_form ? model.load_form->forces() : model.external_forces;
  record.external_force = loads.reshaped(3, loads.size() / 3).rowwise().sum();
  record.potential_energy = model.elastic->value(x) - loads.dot(x);
  for (const auto& p : model.pressures) record.potential_energy += p->value(x);  // docs: path work on open surfaces
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

FrameRecord simulate_frame(Model& model, State& state, int frame, const IterationProgress& progress) {
  const auto t_frame = Clock::now();
  FrameRecord record;
  static_cast<StepStats&>(record) = model.integrator->advance_frame(state, frame, progress);
  record.frame = frame;
  record.time = model.integrator->dynamic() ? frame * model.integrator->frame_duration() : double(frame);
  measure(model, state, record);
  record.seconds = std::chrono::duration<double>(Clock::now() - t_frame).count();
  return record;
}

RunSummary run_scene(const Scene& scene, const RunOptions& options) {
  const auto t_start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t_start).count(); };
  const int frames = options.frames.value_or(scene.frames);
  if (frames < 1) throw Error(fmt::format("must be at least 1, got {}", frames), "--frames");
  if (options.resume && options.out_dir.empty()) throw Error("resuming needs an output directory", "--resume");
  if (!(options.checkpoint_seconds >= 0.0) || !std::isfinite(options.checkpoint_seconds))
    throw Error(fmt::format("must be a finite number of seconds >= 0 (0: after every frame), got {}", options.checkpoint_seconds),
                "--checkpoint-seconds");

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
  const RunFingerprint fingerprint = writing ? fingerprint_run(scene) : RunFingerprint{};
  FrameOutput output(scene, model, writing ? out : std::filesystem::path());
  // The folder is this run's alone until it returns (a second run into it is refused, naming
  // this one's pid); temporary files a killed write left there go first.
  std::optional<FolderLock> lock;
  if (writing) {
    // --resume without a checkpoint fails before the folder is created (read_checkpoint says so);
    // into an existing folder, after the lock (a run still writing it, and so perhaps not yet
    // checkpointed, is named).
    std::error_code ec;
    if (options.resume && !std::filesystem::is_directory(out, ec))
      read_checkpoint(out, fingerprint, integrator, state.x.size(), frames);
    ensure_directory(out);
    lock.emplace(out);
    remove_stale_temporary_files(out);
  }
  auto frame_time = [&](int frame) { return integrator.dynamic() ? frame * integrator.frame_duration() : double(frame); };
  if (options.resume) {
    Checkpoint c = read_checkpoint(out, fingerprint, integrator, state.x.size(), frames);
    summary.frames = read_frame_log(out, c.frame);
    restore_integrator(integrator, c, out);
    state.x = std::move(c.state.x);
    if (integrator.dynamic()) state.v = std::move(c.state.v);
    output.resume_after(c.frame, frame_time);
    first_frame = c.frame + 1;
  } else if (writing) {
    remove_previous_outputs(out);
  }
  if (writing && scene.output.selections) write_selections(out / "selections.json", scene, model);
  // What is written per frame costs the same at frame 10 and at frame 100,000: the frame's
  // files, one line of frames.jsonl, now and then a checkpoint (the state alone). summary.json
  // lists every frame, so it is rewritten only when the frame count has doubled since its last
  // writing (at most twice the frames in all), at the end, and when the run stops on an error.
  // The frames' files and those summaries reach the disk in batches, before each checkpoint
  // (checkpoint_schedule.hpp); the final summary is written through at once.
  std::optional<FrameLog> log;
  if (writing) log.emplace(out, summary.frames);
  DeferredSync frame_files;
  std::optional<CheckpointSchedule> checkpoints;
  if (writing)
    checkpoints.emplace(out, fingerprint, integrator, options.checkpoint_seconds, *log, output, frame_files);
  std::size_t summary_due = 1;
  auto write_summary_now = [&] {
    write_summary(out, scene, model, summary, frames);
    summary_due = 2 * summary.frames.size();
  };
  auto write_frame_files = [&](int frame, double time) {
    DeferredSync::Scope batch(frame_files);
    output.write(frame, time, state);
  };
  if (first_frame == 1) write_frame_files(0, frame_time(0));

  // ---- one frame loop for every integrator
  try {
    for (int frame = first_frame; frame <= frames; ++frame) {
      if (options.progress) options.progress({frame, frames, 0, 0.0, elapsed(), false, nullptr});
      std::vector<double> residuals;  // per Newton iteration, for summary.json and `sinew plot`
      auto progress = [&](int iteration, double residual) {
        residuals.push_back(residual);
        if (options.progress) options.progress({frame, frames, iteration, residual, elapsed(), false, nullptr});
      };
      FrameRecord record = simulate_frame(model, state, frame, progress);
      record.residuals = std::move(residuals);
      summary.frames.push_back(record);
      write_frame_files(frame, record.time);
      if (writing) {
        log->append(record);
        // Only a converged frame, so --resume never continues from a failed state.
        if (record.converged) checkpoints->converged({frame, state, integrator.checkpoint_state()});
        if (summary.frames.size() >= summary_due) {
          DeferredSync::Scope batch(frame_files);
          write_summary_now();
        }
      }
      if (options.progress) options.progress({frame, frames, record.newton_iterations, record.residual, elapsed(), true, &summary.frames.back()});
      if (!record.converged) break;  // later frames would start from an unsolved state
    }
  } catch (...) {
    // The frames before the error still get their checkpoint and summary; the error is what
    // the caller sees.
    if (writing) {
      try {
        checkpoints->commit();
      } catch (...) {
      }
      try {
        write_summary_now();
      } catch (...) {
      }
    }
    throw;
  }
  if (writing) {
    checkpoints->commit();  // the last converged frame (a failed frame's run stops above)
    write_summary_now();
  }
  summary.x = state.x;
  return summary;
}

}  // namespace sinew
