#pragma once
// When a run writes checkpoint.json, and what reaches the disk before it. Writing and fsyncing
// every frame's files and a checkpoint after each frame cost paper 001's small scenes several
// times their solver time, so the frames' files are written without waiting for the disk
// (io/deferred_sync.hpp) and a checkpoint is written once `output.checkpoint_seconds` of wall
// clock have passed since the last one, and always for the run's last converged frame (at its
// end, when a frame fails, and when it stops on an error). Before each checkpoint the frames'
// files, simulation.pvd and frames.jsonl are made durable, so the checkpoint never refers to
// output that a crash could lose; a crash loses at most the frames after the last checkpoint,
// which --resume then computes again.
#include <chrono>
#include <filesystem>
#include <optional>

#include "sinew/io/deferred_sync.hpp"
#include "sinew/run/checkpoint.hpp"
#include "sinew/run/frame_log.hpp"
#include "sinew/run/frame_output.hpp"

namespace sinew {

class CheckpointSchedule {
 public:
  // `files` holds the frames' files written since the last checkpoint (the caller writes them in
  // a DeferredSync::Scope of it). interval_seconds = 0 checkpoints every converged frame.
  CheckpointSchedule(std::filesystem::path out, const RunFingerprint& fingerprint, const Integrator& integrator,
                     double interval_seconds, FrameLog& log, FrameOutput& output, DeferredSync& files);

  // After a converged frame (its files and its line of frames.jsonl written): remembers the
  // checkpoint and writes it when the interval has passed since the last one.
  void converged(Checkpoint checkpoint);

  // Makes the output written so far durable and writes the remembered checkpoint if it is not
  // yet on the disk: at the run's end, after a failed frame, when the run stops on an error.
  void commit();

  // Checkpoints written so far (tests count them).
  int written() const { return written_; }

 private:
  using Clock = std::chrono::steady_clock;
  std::filesystem::path out_;
  const RunFingerprint& fingerprint_;
  const Integrator& integrator_;
  Clock::duration interval_;
  FrameLog& log_;
  FrameOutput& output_;
  DeferredSync& files_;
  std::optional<Checkpoint> pending_;  // the last converged frame, not yet written
  Clock::time_point last_ = Clock::now();
  int written_ = 0;
};

}  // namespace sinew
