// What a run writes per frame does not grow with the frames before it (docs/hardening.md,
// "Per-frame cost"): one line of frames.jsonl per frame, a checkpoint of the state alone, and
// summary.json rewritten only when the frame count has doubled, at the end, and on an error.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/run/frame_log.hpp"
#include "sinew/run/run_summary.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

using nlohmann::json;
using test::TempDir;

json bar(double per_frame) {
  json j = json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.5, 0.5]}, "cells": [2, 1, 1]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "boundary": [
      {"name": "left", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}},
      {"name": "right", "select": {"plane": {"point": [1, 0, 0], "normal": [1, 0, 0]}},
       "motion": {"type": "translate", "per_frame": [0.001, 0, 0]}}
    ],
    "output": {"vtu": false, "obj": false},
    "frames": 40
  })");
  j["boundary"][1]["motion"]["per_frame"][0] = per_frame;
  return j;
}

json read_json(const std::filesystem::path& p) { return json::parse(test::read_file(p)); }

int lines_of(const std::filesystem::path& p) {
  const std::string text = test::read_file(p);
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

TEST(FrameLog, EachFrameAddsOneLineAndTheCheckpointDoesNotGrow) {
  TempDir dir;
  const Scene scene = load_scene(dir.write("scene.json", bar(0.001).dump()));
  RunOptions o;
  o.out_dir = dir / "out";
  o.checkpoint_seconds = 0.0;  // a checkpoint after every frame, to measure each
  std::vector<int> summary_frames, log_lines;
  std::vector<std::uintmax_t> checkpoint_bytes;
  o.progress = [&](const ProgressEvent& e) {
    if (!e.frame_done) return;
    summary_frames.push_back(read_json(o.out_dir / "summary.json")["frames_completed"]);
    log_lines.push_back(lines_of(o.out_dir / FrameLog::kFileName));
    checkpoint_bytes.push_back(std::filesystem::file_size(o.out_dir / "checkpoint.json"));
  };
  const RunSummary s = run_scene(scene, o);
  ASSERT_EQ(s.frames.size(), 40u);
  for (int f = 1; f <= 40; ++f) {
    SCOPED_TRACE(f);
    EXPECT_EQ(log_lines[f - 1], f);
    // summary.json at frames 1, 2, 4, 8, 16, 32: the largest power of two up to f.
    int due = 1;
    while (2 * due <= f) due *= 2;
    EXPECT_EQ(summary_frames[f - 1], due);
  }
  // The state alone: the same size (to a few digits' difference in the numbers) at frame 40 as at 2.
  EXPECT_LT(static_cast<double>(checkpoint_bytes.back()), 1.1 * static_cast<double>(checkpoint_bytes[1]));
  // At the end summary.json lists every frame, the same records as frames.jsonl.
  const json summary = read_json(o.out_dir / "summary.json");
  ASSERT_EQ(summary["frames_completed"], 40);
  ASSERT_EQ(summary["frames"].size(), 40u);
  const std::vector<FrameRecord> logged = read_frame_log(o.out_dir, 40);
  for (int f = 0; f < 40; ++f) EXPECT_EQ(frame_to_json(logged[f]), summary["frames"][f]) << f;
}

TEST(FrameLog, ARunStoppedByAnErrorLeavesTheSummaryOfTheFramesBeforeIt) {
  // Frame 3's output cannot be written (a folder holds its name): the run stops with that error,
  // after frames 1 to 3 were computed.
  TempDir dir;
  json j = bar(0.001);
  j["output"]["vtu"] = true;
  const Scene scene = load_scene(dir.write("scene.json", j.dump()));
  RunOptions o;
  o.out_dir = dir / "out";
  std::filesystem::create_directories(o.out_dir / "frame_0003.vtu");
  try {
    run_scene(scene, o);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    test::expect_contains(e.what(), {"frame_0003.vtu", "is a directory"});
  }
  const json summary = read_json(o.out_dir / "summary.json");
  EXPECT_EQ(summary["frames_completed"], 3);
  EXPECT_EQ(summary["frames_requested"], 40);
  EXPECT_EQ(lines_of(o.out_dir / FrameLog::kFileName), 2);  // frame 3 stopped before its line
}

}  // namespace
}  // namespace sinew
