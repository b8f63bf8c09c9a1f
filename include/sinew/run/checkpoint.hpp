#pragma once
// The checkpoint of a run, one format for every integrator: written after each converged frame,
// it holds the state (positions; velocities for dynamics), the integrator's own state (e.g. the
// energy-limited stepper's multipliers), the frames so far and simulation.pvd's entries, and
// resumes only the scene file and the integrator that wrote it.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "sinew/integrator/integrator.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {

struct Checkpoint {
  int frame = 0;  // the last converged frame
  State state;
  nlohmann::json integrator_state = nlohmann::json::object();
  std::vector<FrameRecord> frames;
  std::vector<std::pair<double, std::string>> pvd;
};

// Writes out/checkpoint.json atomically.
void write_checkpoint(const std::filesystem::path& out, const std::string& scene_fingerprint,
                      const Integrator& integrator, const Checkpoint& checkpoint);

// Reads out/checkpoint.json for a scene with this fingerprint, run by this integrator, with
// `dofs` DOFs; throws a sinew::Error naming the file when there is none, it is corrupt, or it
// belongs to another scene, mesh or kind of run.
Checkpoint read_checkpoint(const std::filesystem::path& out, const std::string& scene_fingerprint,
                           const Integrator& integrator, Eigen::Index dofs);

}  // namespace sinew
