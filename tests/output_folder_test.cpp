// An output folder belongs to one run at a time (io/folder_lock.hpp): a second run into it is
// refused naming the folder and the first run's pid, and writes nothing. A run cleans up the
// hidden temporary files a killed write left there (io/atomic_file.hpp), and only those.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/io/folder_lock.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

using test::error_message;
using test::expect_contains;
using test::TempDir;

Scene small_scene(const TempDir& dir) {
  return load_scene(dir.write("scene.json", R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.5, 0.5]}, "cells": [2, 1, 1]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "boundary": [
      {"name": "left", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}},
      {"name": "right", "select": {"plane": {"point": [1, 0, 0], "normal": [1, 0, 0]}},
       "motion": {"type": "translate", "per_frame": [0.05, 0, 0]}}
    ],
    "frames": 2
  })"));
}

RunSummary run_into(const Scene& scene, const std::filesystem::path& out) {
  RunOptions o;
  o.out_dir = out;
  return run_scene(scene, o);
}

TEST(OutputFolder, ASecondLockIsRefusedNamingTheFolderAndTheOwnersPid) {
  TempDir dir;
  {
    FolderLock first(dir.path());
    EXPECT_EQ(test::read_file(dir / FolderLock::kFileName), fmt::format("{}\n", ::getpid()));
    // flock(2) locks belong to the open file, so a second lock in this process conflicts too.
    expect_contains(error_message([&] { FolderLock second(dir.path()); }),
                    {dir.path().string(), "in use by another sinew run", fmt::format("(pid {})", ::getpid())});
  }
  // Released: the lock file is gone and the folder can be locked again.
  EXPECT_FALSE(std::filesystem::exists(dir / FolderLock::kFileName));
  FolderLock again(dir.path());
  EXPECT_TRUE(std::filesystem::exists(dir / FolderLock::kFileName));
}

TEST(OutputFolder, ARunIntoALockedFolderFailsAndWritesNothing) {
  TempDir dir;
  const Scene scene = small_scene(dir);
  const auto out = dir / "out";
  ASSERT_TRUE(run_into(scene, out).all_converged());
  const auto before = test::read_file(out / "summary.json");
  std::filesystem::remove(out / "frame_0002.vtu");
  {
    FolderLock other(out);  // another run holds the folder
    expect_contains(error_message([&] { run_into(scene, out); }),
                    {out.string(), "in use by another sinew run", fmt::format("(pid {})", ::getpid())});
    RunOptions resume;
    resume.out_dir = out;
    resume.resume = true;
    expect_contains(error_message([&] { run_scene(scene, resume); }), {out.string(), "in use by another sinew run"});
  }
  // Nothing was removed, replaced or added by the refused runs.
  EXPECT_EQ(test::read_file(out / "summary.json"), before);
  EXPECT_FALSE(std::filesystem::exists(out / "frame_0002.vtu"));
  // Once free, a run takes the folder and leaves no lock file behind.
  ASSERT_TRUE(run_into(scene, out).all_converged());
  EXPECT_TRUE(std::filesystem::exists(out / "frame_0002.vtu"));
  EXPECT_FALSE(std::filesystem::exists(out / FolderLock::kFileName));
}

TEST(OutputFolder, StaleTemporaryFilesOfKilledWritesAreRemovedAndNothingElse) {
  TempDir dir;
  const Scene scene = small_scene(dir);
  const auto out = dir / "out";
  std::filesystem::create_directories(out);
  // pid_max is at most 2^22 on Linux: pid 999999999 never runs. This process's own pid counts
  // as stale too (a killed run's pid, reused). pid 1 runs (init), so its file stays.
  const std::vector<std::string> stale = {".summary.json.tmp-999999999-0", ".frame_0001.vtu.tmp-999999999-17",
                                          fmt::format(".checkpoint.json.tmp-{}-4", ::getpid())};
  const std::vector<std::string> kept = {".summary.json.tmp-1-0", "notes.tmp-999999999-0", ".notes.tmp-x-1",
                                         ".notes.tmp-999999999", "results.csv", ".hidden"};
  for (const auto& name : stale) std::ofstream(out / name) << "partial";
  for (const auto& name : kept) std::ofstream(out / name) << "someone else's";
  EXPECT_EQ(remove_stale_temporary_files(out), 3);
  for (const auto& name : stale) EXPECT_FALSE(std::filesystem::exists(out / name)) << name;
  for (const auto& name : kept) EXPECT_TRUE(std::filesystem::exists(out / name)) << name;

  // A run does the same before it writes.
  for (const auto& name : stale) std::ofstream(out / name) << "partial";
  ASSERT_TRUE(run_into(scene, out).all_converged());
  for (const auto& name : stale) EXPECT_FALSE(std::filesystem::exists(out / name)) << name;
  for (const auto& name : kept) EXPECT_TRUE(std::filesystem::exists(out / name)) << name;
}

}  // namespace
}  // namespace sinew
