// When a run checkpoints (run/checkpoint_schedule.hpp): after every converged frame with
// checkpoint_seconds = 0, otherwise after the interval and always for the last converged frame
// (at the end, and when the run stops on an error); simulation.pvd and frames.jsonl are on the
// disk before each checkpoint. A resumed run that finds the frames' files and frames.jsonl ahead
// of its checkpoint (a crash between two checkpoints) ends exactly as an uninterrupted run.
// No test depends on the wall clock: the intervals are 0 or longer than any test run.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "sinew/io/folder_lock.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/run/checkpoint.hpp"
#include "sinew/run/frame_log.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::TempDir;

constexpr double kNever = 1e9;  // seconds: longer than any test

// A bar stretched over 10 quasistatic frames, with a .vtu (and so simulation.pvd) per frame.
std::string bar() {
  return R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.5, 0.5]}, "cells": [2, 1, 1]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "boundary": [
      {"name": "left", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}},
      {"name": "right", "select": {"plane": {"point": [1, 0, 0], "normal": [1, 0, 0]}},
       "motion": {"type": "translate", "per_frame": [0.02, 0, 0]}}
    ],
    "solver": {"newton": {"convergence": "absolute", "tolerance": 1e-9}},
    "output": {"vtu": true, "obj": false},
    "frames": 10
  })";
}

int checkpoint_frame(const fs::path& out) {
  return json::parse(test::read_file(out / "checkpoint.json"))["frame"].get<int>();
}

long datasets_in_pvd(const fs::path& out) {
  const std::string text = test::read_file(out / "simulation.pvd");
  long n = 0;
  for (std::size_t at = text.find("<DataSet "); at != std::string::npos; at = text.find("<DataSet ", at + 1)) ++n;
  return n;
}

// What a crash would leave: every file of the folder but the lock (the kernel drops that one).
void copy_folder(const fs::path& from, const fs::path& to) {
  fs::create_directories(to);
  for (const auto& e : fs::directory_iterator(from))
    if (e.path().filename() != FolderLock::kFileName) fs::copy_file(e.path(), to / e.path().filename());
}

TEST(CheckpointSchedule, ZeroSecondsCheckpointsEveryConvergedFrame) {
  TempDir dir;
  const Scene scene = load_scene(dir.write("scene.json", bar()));
  RunOptions o;
  o.out_dir = dir / "out";
  o.checkpoint_seconds = 0.0;
  std::vector<int> checkpoints;
  std::vector<long> listed;
  o.progress = [&](const ProgressEvent& e) {
    if (!e.frame_done) return;
    checkpoints.push_back(checkpoint_frame(o.out_dir));
    listed.push_back(datasets_in_pvd(o.out_dir));
  };
  ASSERT_EQ(run_scene(scene, o).frames.size(), 10u);
  for (int f = 1; f <= 10; ++f) {
    EXPECT_EQ(checkpoints[f - 1], f);
    EXPECT_EQ(listed[f - 1], f + 1);  // frames 0 to f
  }
}

TEST(CheckpointSchedule, ALongIntervalCheckpointsTheRunsEndOnly) {
  TempDir dir;
  const Scene scene = load_scene(dir.write("scene.json", bar()));
  RunOptions o;
  o.out_dir = dir / "out";
  o.checkpoint_seconds = kNever;
  int frames_seen = 0;
  o.progress = [&](const ProgressEvent& e) {
    if (!e.frame_done) return;
    ++frames_seen;
    EXPECT_FALSE(has_checkpoint(o.out_dir)) << e.frame;
    EXPECT_FALSE(fs::exists(o.out_dir / "simulation.pvd")) << e.frame;
    // The frame's own files and its line are there at once (tail -f, a viewer watching the folder).
    EXPECT_TRUE(fs::exists(o.out_dir / fmt::format("frame_{:04d}.vtu", e.frame)));
    EXPECT_EQ(read_frame_log(o.out_dir, e.frame).size(), static_cast<std::size_t>(e.frame));
  };
  run_scene(scene, o);
  EXPECT_EQ(frames_seen, 10);
  EXPECT_EQ(checkpoint_frame(o.out_dir), 10);
  EXPECT_EQ(datasets_in_pvd(o.out_dir), 11);
}

TEST(CheckpointSchedule, AnErrorCheckpointsTheLastConvergedFrameAndTheRunResumesFromIt) {
  TempDir dir;
  const Scene scene = load_scene(dir.write("scene.json", bar()));
  RunOptions whole;
  whole.out_dir = dir / "whole";
  const RunSummary uninterrupted = run_scene(scene, whole);

  RunOptions o;
  o.out_dir = dir / "out";
  o.checkpoint_seconds = kNever;
  fs::create_directories(o.out_dir / "frame_0004.vtu");  // frame 4's output cannot be written
  const std::string message = test::error_message([&] { run_scene(scene, o); });
  test::expect_contains(message, {"frame_0004.vtu", "is a directory"});
  EXPECT_EQ(checkpoint_frame(o.out_dir), 3);
  EXPECT_EQ(datasets_in_pvd(o.out_dir), 4);  // frames 0 to 3

  fs::remove(o.out_dir / "frame_0004.vtu");
  o.resume = true;
  const RunSummary resumed = run_scene(scene, o);
  ASSERT_EQ(resumed.frames.size(), 10u);
  EXPECT_EQ(resumed.x, uninterrupted.x);  // bit for bit
  EXPECT_EQ(test::read_file(o.out_dir / "frame_0010.vtu"), test::read_file(whole.out_dir / "frame_0010.vtu"));
  EXPECT_EQ(datasets_in_pvd(o.out_dir), 11);
}

TEST(CheckpointSchedule, ResumingFromACheckpointBehindTheFilesOfACrashedRunEndsAsTheUninterruptedRun) {
  // The folder a crash at frame 6 leaves when the last checkpoint was frame 3: frames 4 to 6
  // have their files and lines in frames.jsonl, the checkpoint is older.
  TempDir dir;
  const Scene scene = load_scene(dir.write("scene.json", bar()));
  RunOptions o;
  o.out_dir = dir / "whole";
  o.checkpoint_seconds = 0.0;
  std::string checkpoint_of_frame_3;
  o.progress = [&](const ProgressEvent& e) {
    if (!e.frame_done) return;
    if (e.frame == 3) checkpoint_of_frame_3 = test::read_file(o.out_dir / "checkpoint.json");
    if (e.frame == 6) copy_folder(o.out_dir, dir / "crashed");
  };
  const RunSummary uninterrupted = run_scene(scene, o);
  std::ofstream(dir / "crashed" / "checkpoint.json", std::ios::binary) << checkpoint_of_frame_3;

  RunOptions r;
  r.out_dir = dir / "crashed";
  r.resume = true;
  const RunSummary resumed = run_scene(scene, r);
  ASSERT_EQ(resumed.frames.size(), 10u);
  EXPECT_EQ(resumed.x, uninterrupted.x);
  for (int f = 0; f <= 10; ++f) {
    const std::string name = fmt::format("frame_{:04d}.vtu", f);
    EXPECT_EQ(test::read_file(r.out_dir / name), test::read_file(o.out_dir / name)) << name;
  }
  EXPECT_EQ(test::read_file(r.out_dir / "simulation.pvd"), test::read_file(o.out_dir / "simulation.pvd"));
  const std::vector<FrameRecord> log = read_frame_log(r.out_dir, 10);
  for (int f = 1; f <= 10; ++f) EXPECT_EQ(log[f - 1].frame, f);  // frames 4 to 6 once, from the resumed run
  EXPECT_EQ(test::read_file(r.out_dir / FrameLog::kFileName).find("\n\n"), std::string::npos);
}

TEST(CheckpointSchedule, AnIntervalThatIsNotANumberOfSecondsIsRefused) {
  TempDir dir;
  const Scene scene = load_scene(dir.write("scene.json", bar()));
  for (double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    RunOptions o;
    o.out_dir = dir / "out";
    o.checkpoint_seconds = bad;
    test::expect_contains(test::error_message([&] { run_scene(scene, o); }), {"--checkpoint-seconds", ">= 0"});
    EXPECT_FALSE(fs::exists(o.out_dir));  // refused before anything is written
  }
}

}  // namespace
}  // namespace sinew
