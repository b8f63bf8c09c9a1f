#include "sinew/run/checkpoint_schedule.hpp"

#include <algorithm>
#include <utility>

namespace sinew {
namespace {

constexpr double kLongest = 1e9;  // seconds (~32 years); keeps the clock's ticks from overflowing

}  // namespace

CheckpointSchedule::CheckpointSchedule(std::filesystem::path out, const RunFingerprint& fingerprint,
                                       const Integrator& integrator, double interval_seconds, FrameLog& log,
                                       FrameOutput& output, DeferredSync& files)
    : out_(std::move(out)),
      fingerprint_(fingerprint),
      integrator_(integrator),
      interval_(std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(std::min(interval_seconds, kLongest)))),
      log_(log),
      output_(output),
      files_(files) {}

void CheckpointSchedule::converged(Checkpoint checkpoint) {
  pending_ = std::move(checkpoint);
  if (Clock::now() - last_ >= interval_) commit();
}

void CheckpointSchedule::commit() {
  // Taken out first: if making the output durable fails, this checkpoint is never written (a
  // later commit, such as the one when the run stops on that error, must not refer to it).
  std::optional<Checkpoint> checkpoint = std::move(pending_);
  pending_.reset();
  {
    DeferredSync::Scope scope(files_);
    output_.write_collection();
  }
  // Everything the checkpoint refers to reaches the disk first (resume reads frames.jsonl up
  // to its frame; the frames' files must not be lost behind it).
  files_.sync();
  log_.sync();
  if (checkpoint) {
    write_checkpoint(out_, fingerprint_, integrator_, *checkpoint);
    ++written_;
  }
  last_ = Clock::now();
}

}  // namespace sinew
