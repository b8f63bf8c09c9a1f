// Obstacle and bone files (run/shape_output.hpp): a shape that did not move since the previous
// output frame gets that frame's files under its own names as hard links (the same bytes, nothing
// written again); a moving one is written each frame.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <fmt/format.h>

#include "io_test_support.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/io/deferred_sync.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

using test::read_file;
using test::TempDir;

ino_t inode(const std::filesystem::path& p) {
  struct stat st {};
  EXPECT_EQ(::stat(p.c_str(), &st), 0) << p;
  return st.st_ino;
}

TEST(ShapeOutput, AShapeThatDidNotMoveIsLinkedAndAMovingOneWritten) {
  TempDir dir;
  const auto scene = dir.write("scene.json", R"({
    "mesh": {"box": {"min": [-0.5, -0.5, 0], "max": [0.5, 0.5, 0.2]}, "cells": [4, 4, 1]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.45},
    "boundary": [{"name": "base", "select": {"plane": {"point": [0, 0, 0], "normal": [0, 0, -1]}}}],
    "obstacles": [
      {"name": "floor", "type": "plane", "point": [0, 0, -0.5], "normal": [0, 0, 1], "stiffness": 1e8},
      {"name": "indenter", "type": "sphere", "center": [0, 0, 0.6], "radius": 0.25, "stiffness": 1e8,
       "motion": {"type": "translate", "per_frame": [0, 0, -0.05]}}
    ],
    "frames": 3
  })");
  RunOptions o;
  o.out_dir = dir / "out";
  run_scene(load_scene(scene), o);
  for (const char* ext : {"vtu", "obj"}) {
    SCOPED_TRACE(ext);
    const auto floor = [&](int f) { return o.out_dir / fmt::format("obstacle_floor_{:04d}.{}", f, ext); };
    const auto indenter = [&](int f) { return o.out_dir / fmt::format("obstacle_indenter_{:04d}.{}", f, ext); };
    for (int f = 1; f <= 3; ++f) {
      EXPECT_EQ(inode(floor(f)), inode(floor(0)));
      EXPECT_EQ(read_file(floor(f)), read_file(floor(0)));
      EXPECT_NE(inode(indenter(f)), inode(indenter(f - 1)));
      EXPECT_NE(read_file(indenter(f)), read_file(indenter(f - 1)));
    }
  }
  for (const auto& e : std::filesystem::directory_iterator(o.out_dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();

  // A fresh run into the folder writes its files anew: the earlier run's links are replaced.
  run_scene(load_scene(scene), o);
  EXPECT_EQ(inode(o.out_dir / "obstacle_floor_0003.obj"), inode(o.out_dir / "obstacle_floor_0000.obj"));
}

TEST(ShapeOutput, LinkingReplacesTheTargetWholeOrSaysThatItCannot) {
  TempDir dir;
  const auto source = dir.write("a.txt", "content");
  const auto target = dir.write("b.txt", "old");
  DeferredSync batch;
  {
    DeferredSync::Scope scope(batch);
    EXPECT_TRUE(link_file_atomically(source, target));
  }
  EXPECT_EQ(read_file(target), "content");
  EXPECT_EQ(inode(target), inode(source));
  EXPECT_EQ(batch.pending(), 0u);  // no descriptor: only the folder waits for the sync
  batch.sync();
  EXPECT_FALSE(link_file_atomically(dir / "missing.txt", dir / "c.txt"));  // the caller writes instead
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a.txt", "b.txt"}));
  EXPECT_FALSE(link_file_atomically(source, dir / "no" / "such" / "d.txt"));
}

}  // namespace
}  // namespace sinew
