// selections.json ("output": {"selections": true}): the vertices (and faces) each boundary
// condition and load selects, as the model uses them; not written unless asked for.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "sinew/run/selection_output.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

RunOptions one_frame_into(const std::filesystem::path& out) {
  RunOptions o;
  o.out_dir = out;
  o.frames = 1;
  return o;
}

using nlohmann::json;

json scene_json() {
  return json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.5, 0.5]}, "cells": [4, 2, 2]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "boundary": [{"name": "wall", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}},
                 {"select": {"indices": [7, 3]}}],
    "loads": {"point": [{"select": {"indices": [20]}, "force": [0, 0, -1]}],
              "traction": [{"select": {"plane": {"point": [1, 0, 0], "normal": [1, 0, 0]}}, "traction": [1, 0, 0]}],
              "pressure": [{"select": {"box": {"min": [0, 0, 0.5], "max": [0.5, 0.5, 0.5]}}, "pressure": 10}]},
    "output": {"selections": true, "vtu": false, "obj": false}})");
}

TEST(SelectionOutput, ListsTheVerticesAndFacesOfEveryConditionAndLoad) {
  test::TempDir dir;
  const auto file = dir.write("scene.json", scene_json().dump());
  const Scene scene = load_scene(file);
  const Model model = build_model(scene);
  const RunSummary r = run_scene(scene, one_frame_into(dir / "out"));
  ASSERT_TRUE(r.all_converged());
  const json j = json::parse(test::read_file(dir / "out" / "selections.json"));
  const VolumeMesh& mesh = model.disc->mesh();
  ASSERT_EQ(j["boundary"].size(), 2u);
  EXPECT_EQ(j["boundary"][0]["name"], "wall");
  EXPECT_EQ(j["boundary"][0]["path"], "/boundary/0");
  const std::vector<int> wall = j["boundary"][0]["vertices"];
  EXPECT_EQ(wall, (*model.kinematics)[0].vertices);
  EXPECT_EQ(wall.size(), 9u);
  for (int v : wall) EXPECT_EQ(mesh.vertices(v, 0), 0.0);
  EXPECT_EQ(j["boundary"][1]["vertices"], json({3, 7}));
  ASSERT_EQ(j["loads"].size(), 3u);
  EXPECT_EQ(j["loads"][0]["path"], "/loads/point/0");
  EXPECT_EQ(j["loads"][0]["vertices"], json({20}));
  EXPECT_FALSE(j["loads"][0].contains("faces"));
  EXPECT_EQ(j["loads"][1]["path"], "/loads/traction/0");
  EXPECT_EQ(j["loads"][1]["faces"].size(), 4u);  // the 2 x 2 end face
  EXPECT_EQ(j["loads"][2]["path"], "/loads/pressure/0");
  EXPECT_EQ(j["loads"][2]["vertices"].size(), 9u);
  const std::vector<std::vector<int>> faces = j["loads"][2]["faces"];
  EXPECT_EQ(faces, model.pressures[0]->faces());
  EXPECT_EQ(faces.size(), 4u);
}

TEST(SelectionOutput, WrittenOnlyWhenAskedAndRemovedByAFreshRun) {
  test::TempDir dir;
  json j = scene_json();
  const auto out = dir / "out";
  run_scene(load_scene(dir.write("scene.json", j.dump())), one_frame_into(out));
  ASSERT_TRUE(std::filesystem::exists(out / "selections.json"));
  j["output"].erase("selections");
  run_scene(load_scene(dir.write("scene.json", j.dump())), one_frame_into(out));
  EXPECT_FALSE(std::filesystem::exists(out / "selections.json"));  // a stale one would mislead
  EXPECT_TRUE(std::filesystem::exists(out / "summary.json"));
}

}  // namespace
}  // namespace sinew
