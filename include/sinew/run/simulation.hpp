#pragma once
// Runs a scene: builds its model (model/model.hpp) and advances it frame by frame with its
// integrator (quasistatic, backward Euler, semi-implicit or energy-limited: one frame loop for
// all), writing each frame's outputs atomically (frame_output.hpp), summary.json
// (run_summary.hpp) and a checkpoint (checkpoint.hpp) so an interrupted run can be resumed.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sinew/integrator/integrator.hpp"
#include "sinew/model/scene.hpp"

namespace sinew {
struct Model;  // sinew/model/model.hpp
}

namespace sinew {

// A frame's stats (iterations, residual, times, the integrator's counters) and what was measured
// on its final state.
struct FrameRecord : StepStats {
  int frame = 0;
  double time = 0.0;  // simulated seconds at the frame's end (quasistatic runs: the frame number)
  double volume = 0.0;
  double min_J = 0.0;
  // The residual after each Newton iteration of the frame (every time step's, in order; for
  // energy-limited dynamics the constraint error after each step), for convergence plots.
  std::vector<double> residuals;
  // Force each boundary condition (scene order) exerts on the body: the measured force of a
  // stretch test; at equilibrium their sum balances the external loads.
  std::vector<Eigen::Vector3d> reactions;
  Eigen::Vector3d external_force = Eigen::Vector3d::Zero();  // sum of the loads at this frame's amplitudes
  // Energies of the frame's state (kinetic is zero in quasistatics) and obstacle contact.
  double kinetic_energy = 0.0, potential_energy = 0.0;
  int contacts = 0;               // penetrating (boundary vertex, obstacle) pairs (penalty contact)
  double max_penetration = 0.0;  // deepest penetration into an obstacle (penalty contact)
  // Self-contact (reference-map penalty): samples held by a contact spring, and the deepest
  // surface sample found inside the body at the frame's state (0 without self-contact).
  int self_contacts = 0;
  double self_penetration = 0.0;
};

struct ProgressEvent {
  int frame = 0, frames = 0;
  int newton_iteration = 0;  // 0 at the start of a frame
  double residual = 0.0;
  double elapsed = 0.0;       // seconds since the run started
  bool frame_done = false;
  const FrameRecord* record = nullptr;  // set when frame_done
};

struct RunOptions {
  std::filesystem::path out_dir;  // empty: write nothing
  std::optional<int> frames;      // overrides the scene's frame count
  bool resume = false;            // continue from out_dir's checkpoint
  // Wall-clock seconds between checkpoints, 0: after every converged frame; the last converged
  // frame is always checkpointed (run/checkpoint_schedule.hpp).
  double checkpoint_seconds = 1.0;
  std::function<void(const ProgressEvent&)> progress;
  std::function<void(const std::string&)> warning;  // each of the model's warnings, before the first frame
  bool strict = false;                              // warnings are errors
};

struct RunSummary {
  Eigen::Index vertices = 0, elements = 0;
  double rest_volume = 0.0;
  Eigen::Vector3d external_force = Eigen::Vector3d::Zero();  // sum of gravity, point loads, tractions at amplitude 1
  std::vector<std::string> warnings;  // the model's (Model::warnings), also printed by the CLI
  std::vector<FrameRecord> frames;  // including frames from before a resume; stops at the
                                    // first frame that did not converge
  Eigen::VectorXd x;                // final positions
  bool all_converged() const;
};

// Advances `state` over frame `frame` with the model's integrator and measures the result (volume,
// J, reactions, energies, contact); `seconds` is the frame's wall time. run_scene's frame loop and
// Session::step (session.hpp) both take their frames from here.
FrameRecord simulate_frame(Model& model, State& state, int frame, const IterationProgress& progress);

// Builds and validates the whole model (mesh, material, selections, loads) before writing
// anything; a fresh run then replaces the files of an earlier run in out_dir. The run stops
// after the first frame that does not converge (its state is still written, for inspection;
// the checkpoint keeps the last converged frame).
RunSummary run_scene(const Scene& scene, const RunOptions& options);

// Removes the files an earlier run wrote into out (frames, surfaces, pvd, summary, checkpoint).
void remove_previous_outputs(const std::filesystem::path& out);

}  // namespace sinew
