#pragma once
// out/frames.jsonl: one line per finished frame (the record of run_summary.hpp), appended as
// each frame ends (`tail -f` follows it) and made durable before each checkpoint. It is what keeps a run's cost per frame from
// growing with the frames before it: summary.json, which lists every frame, is rewritten only at
// frame counts that double and at the end, and the checkpoint holds the state alone; a resumed
// run takes its earlier frames from here.
#include <filesystem>
#include <vector>

#include "sinew/run/simulation.hpp"

namespace sinew {

class FrameLog {
 public:
  static constexpr const char* kFileName = "frames.jsonl";

  // Starts out/frames.jsonl (written atomically) with the records `kept`: none for a fresh run,
  // the frames up to the checkpoint for a resumed one.
  FrameLog(const std::filesystem::path& out, const std::vector<FrameRecord>& kept);
  ~FrameLog();
  FrameLog(const FrameLog&) = delete;
  FrameLog& operator=(const FrameLog&) = delete;

  // Appends the record as one line (one write(2)); a sinew::Error names the file and the reason.
  void append(const FrameRecord& record);

  // Waits until every appended line reached the disk (before a checkpoint that counts them).
  void sync();

 private:
  std::filesystem::path file_;
  int fd_ = -1;
};

// The records of frames 1 to `frames` from out/frames.jsonl, each checked; lines after them (a
// frame past the checkpoint, a line a killed run left unfinished) are ignored. A sinew::Error
// names the file, the line and the JSON path when one is missing, out of order or malformed.
std::vector<FrameRecord> read_frame_log(const std::filesystem::path& out, int frames);

}  // namespace sinew
