#pragma once
// The checkpoint of a run (out/checkpoint.json), one format for every integrator: written after
// each converged frame, it holds the state (positions; velocities for dynamics) and the
// integrator's own state (e.g. the energy-limited stepper's multipliers), nothing that grows
// with the frames (their records are in frames.jsonl, frame_log.hpp). It resumes only the run that wrote it: the same integrator, the
// same scene file and the same bytes in every file the scene reads (mesh, surfaces, rig, bone
// meshes). Everything read from it is checked (docs/hardening.md): a hostile or damaged
// checkpoint is a sinew::Error naming the file and JSON path, never a run that goes astray.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sinew/integrator/integrator.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {

// What a checkpoint must match to be resumed.
struct RunFingerprint {
  struct Input {
    std::string name;            // as the checkpoint lists it: relative to the scene's folder
    std::filesystem::path path;  // where it is read from
    std::string fingerprint;
  };
  std::string scene;          // of the scene file's bytes
  std::vector<Input> inputs;  // every other file the scene reads (scene_input_files)
};

// Fingerprints (size and 64-bit FNV-1a hash of the bytes) of the scene file and of every file it
// reads; a sinew::Error names a file that cannot be read.
RunFingerprint fingerprint_run(const Scene& scene);

struct Checkpoint {
  int frame = 0;  // the last converged frame
  State state;
  nlohmann::json integrator_state = nlohmann::json::object();
};

// Whether out/checkpoint.json exists (read_checkpoint says why one cannot be resumed).
bool has_checkpoint(const std::filesystem::path& out);

// Writes out/checkpoint.json atomically.
void write_checkpoint(const std::filesystem::path& out, const RunFingerprint& fingerprint, const Integrator& integrator,
                      const Checkpoint& checkpoint);

// Reads out/checkpoint.json for a run of `frames_requested` frames with these inputs, run by this
// integrator, with `dofs` DOFs. Throws a sinew::Error naming the checkpoint (and the JSON path)
// when there is none, it is malformed, its frame is not a whole number from 1 to the frames
// requested, or it belongs to another kind of run or mesh; naming the input file when one of the
// scene's files changed since it was written.
Checkpoint read_checkpoint(const std::filesystem::path& out, const RunFingerprint& fingerprint,
                           const Integrator& integrator, Eigen::Index dofs, int frames_requested);

// Gives the integrator the checkpoint's integrator state; a malformed one is a sinew::Error
// naming out/checkpoint.json.
void restore_integrator(Integrator& integrator, const Checkpoint& checkpoint, const std::filesystem::path& out);

}  // namespace sinew
