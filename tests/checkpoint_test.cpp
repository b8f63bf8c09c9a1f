// --resume trusts nothing in the output folder: a checkpoint with a frame number that is huge,
// negative or fractional, values of the wrong type or a hostile integrator state, and frame
// records (frames.jsonl) missing, out of order or damaged are refused naming the file and JSON
// path; a checkpoint resumes only while every file the scene reads (mesh, embedded surface, rig,
// bone mesh) is unchanged.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/run/checkpoint.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

using nlohmann::json;
using test::error_message;
using test::expect_contains;
using test::TempDir;

// A closed axis-aligned cube [lo, hi]^3 as OBJ text (outward normals).
std::string cube_obj(double lo, double hi) {
  std::string s;
  for (int i = 0; i < 8; ++i) s += fmt::format("v {} {} {}\n", i & 1 ? hi : lo, i & 2 ? hi : lo, i & 4 ? hi : lo);
  // Two triangles per face, counter-clockwise seen from outside (1-based indices).
  s += "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\n";
  s += "f 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";
  return s;
}

// The two-hexahedron MEDIT mesh of tests/data, its left end pinned and right end pulled.
json mesh_file_scene() {
  return json::parse(R"({
    "mesh": {"file": "hex2.mesh"},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "boundary": [
      {"name": "left", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}},
      {"name": "right", "select": {"plane": {"point": [2, 0, 0], "normal": [1, 0, 0]}},
       "motion": {"type": "translate", "per_frame": [0.05, 0, 0]}}
    ],
    "output": {"vtu": false, "obj": false},
    "frames": 3
  })");
}

// A lattice with an embedded surface and a rig file whose bone is a mesh.
json rigged_scene() {
  return json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "cells": [4, 4, 4], "embed": "surface.obj"},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.3},
    "boundary": [{"name": "bottom", "select": {"plane": {"point": [0, 0, 0], "normal": [0, 0, -1]}}}],
    "rig": "rig.json",
    "output": {"vtu": false, "obj": false},
    "frames": 3
  })");
}

json rig() {
  return json::parse(R"({
    "bones": [{"name": "block", "mesh": "bone.obj",
               "keys": [{"frame": 0}, {"frame": 3, "translation": [0, 0, 0.06]}]}]
  })");
}

RunSummary run(const std::filesystem::path& scene, const std::filesystem::path& out, int frames, bool resume) {
  RunOptions o;
  o.out_dir = out;
  o.frames = frames;
  o.resume = resume;
  return run_scene(load_scene(scene), o);
}

json read_json(const std::filesystem::path& p) { return json::parse(test::read_file(p)); }
void write_json(const std::filesystem::path& p, const json& j) { std::ofstream(p) << j.dump(); }

TEST(Checkpoint, FrameNumbersThatAreNotAWholeFrameOfThisRunAreRefused) {
  TempDir dir;
  dir.write("hex2.mesh", test::read_file(test::data_path("hex2.mesh")));
  const auto scene = dir.write("scene.json", mesh_file_scene().dump());
  const auto out = dir / "out";
  ASSERT_TRUE(run(scene, out, 2, false).all_converged());
  const json good = read_json(out / "checkpoint.json");
  ASSERT_EQ(good["frame"], 2);

  for (const json& frame : {json(2147483647), json(-1), json(0), json(2.5), json(1e300), json("2"), json(4),
                            json(9223372036854775807LL), json(18446744073709551615ULL), json(nullptr)}) {
    SCOPED_TRACE(frame.dump());
    json bad = good;
    bad["frame"] = frame;
    write_json(out / "checkpoint.json", bad);
    expect_contains(error_message([&] { run(scene, out, 3, true); }), {"checkpoint.json: /frame: "});
  }
  // Frame 2 of a run now asking for 1 frame: past its end.
  write_json(out / "checkpoint.json", good);
  expect_contains(error_message([&] { run(scene, out, 1, true); }),
                  {"checkpoint.json: /frame: ", "at frame 2, past the 1 frame(s)"});
  // The good one still resumes, to frame 3 with each frame once.
  const RunSummary resumed = run(scene, out, 3, true);
  ASSERT_EQ(resumed.frames.size(), 3u);
  for (int f = 0; f < 3; ++f) EXPECT_EQ(resumed.frames[f].frame, f + 1);
}

TEST(Checkpoint, DamagedContentIsRefusedNamingTheJsonPath) {
  TempDir dir;
  dir.write("hex2.mesh", test::read_file(test::data_path("hex2.mesh")));
  const auto scene = dir.write("scene.json", mesh_file_scene().dump());
  const auto out = dir / "out";
  ASSERT_TRUE(run(scene, out, 2, false).all_converged());
  const json good = read_json(out / "checkpoint.json");
  auto refused = [&](const std::function<void(json&)>& damage, const std::vector<std::string>& words) {
    json bad = good;
    damage(bad);
    write_json(out / "checkpoint.json", bad);
    const std::string message = error_message([&] { run(scene, out, 3, true); });
    EXPECT_NE(message.find("checkpoint.json"), std::string::npos) << message;
    for (const auto& w : words) EXPECT_NE(message.find(w), std::string::npos) << w << " not in: " << message;
  };
  refused([](json& j) { j["x"][3] = "1"; }, {"/x/3", "number"});
  refused([](json& j) { j["x"].erase(0); }, {"/x", "DOFs"});
  refused([](json& j) { j["integrator_state"] = 3; }, {"/integrator_state", "object"});
  refused([](json& j) { j["inputs"] = json::array(); }, {"/inputs", "object"});
  refused([](json& j) { j["format"] = 2; }, {"older or another kind"});
  // Nested deeper than any Sinew file: refused while parsing, before anything recurses.
  std::ofstream(out / "checkpoint.json") << R"({"format": 3, "integrator_state": )" << std::string(5000, '[')
                                         << std::string(5000, ']') << "}";
  expect_contains(error_message([&] { run(scene, out, 3, true); }), {"checkpoint.json", "nested more than"});
  std::ofstream(out / "checkpoint.json") << R"({"format": 3, "format": 3})";
  expect_contains(error_message([&] { run(scene, out, 3, true); }), {"checkpoint.json", "duplicate key"});
}

TEST(Checkpoint, FrameRecordsMustBeTheFramesUpToTheCheckpointInOrder) {
  TempDir dir;
  dir.write("hex2.mesh", test::read_file(test::data_path("hex2.mesh")));
  const auto scene = dir.write("scene.json", mesh_file_scene().dump());
  const auto out = dir / "out";
  ASSERT_TRUE(run(scene, out, 2, false).all_converged());
  const std::string good = test::read_file(out / "frames.jsonl");
  std::vector<json> lines;
  for (size_t at = 0, end; (end = good.find('\n', at)) != std::string::npos; at = end + 1)
    lines.push_back(json::parse(good.substr(at, end - at)));
  ASSERT_EQ(lines.size(), 2u);
  auto jsonl = [](const std::vector<json>& records) {
    std::string text;
    for (const json& r : records) text += r.dump() + "\n";
    return text;
  };
  auto refused = [&](const std::string& text, const std::vector<std::string>& words) {
    dir.write("out/frames.jsonl", text);
    std::vector<std::string> all = {(out / "frames.jsonl").string()};
    all.insert(all.end(), words.begin(), words.end());
    expect_contains(error_message([&] { run(scene, out, 3, true); }), all);
  };
  refused(jsonl({lines[0], lines[0]}), {": line 2: /frame: is frame 1, expected frame 2"});
  refused(jsonl({lines[1], lines[0]}), {": line 1: /frame: is frame 2, expected frame 1"});
  refused(jsonl({lines[0]}), {"holds 1 whole frame record(s), the checkpoint is at frame 2"});
  refused(jsonl({lines[0]}) + lines[1].dump(), {"holds 1 whole frame record(s)"});  // the last line cut short
  refused("", {"holds 0 whole frame record(s)"});
  json bad = lines[0];
  bad["newton_iterations"] = 1.5;
  refused(jsonl({bad, lines[1]}), {": line 1: /newton_iterations: must be a whole number"});
  bad = lines[1];
  bad["counters"] = json::array();
  refused(jsonl({lines[0], bad}), {": line 2: /counters: must be an object"});
  bad = lines[0];
  bad.erase("residual");
  refused(jsonl({bad, lines[1]}), {": line 1: /residual: missing"});
  refused(jsonl({lines[0]}) + std::string(3000, '[') + "\n", {": line 2", "nested more than"});
  refused(jsonl({lines[0]}) + "{\"frame\": 2, \"frame\": 2}\n", {": line 2", "duplicate key"});
  std::filesystem::remove(out / "frames.jsonl");
  expect_contains(error_message([&] { run(scene, out, 3, true); }), {"frames.jsonl", "missing or unreadable"});

  // Records past the checkpoint (a frame that failed after it, a line a killed run left
  // unfinished) are dropped; the resumed run continues the records from the checkpoint's frame.
  json failed = lines[1];
  failed["frame"] = 3;
  failed["converged"] = false;
  dir.write("out/frames.jsonl", jsonl({lines[0], lines[1], failed}) + "{\"frame\": 4, \"ti");
  const RunSummary resumed = run(scene, out, 3, true);
  ASSERT_EQ(resumed.frames.size(), 3u);
  EXPECT_TRUE(resumed.frames[2].converged);
  const std::string after = test::read_file(out / "frames.jsonl");
  EXPECT_EQ(after.substr(0, good.size()), good);
  EXPECT_EQ(std::count(after.begin(), after.end(), '\n'), 3);
}

TEST(Checkpoint, TheEnergyLimitedStatesMultiplierKeysMustNameConstraintsOfTheMesh) {
  // The stepper indexes element rows by key: a key past the mesh once read past its elements.
  TempDir dir;
  for (const char* name : {"scene.json", "cube.obj"})
    dir.write(name, test::read_file(test::data_path(std::string("checkpoint_scene/") + name)));
  const auto scene = dir / "scene.json";
  const auto out = dir / "out";
  ASSERT_TRUE(run(scene, out, 2, false).all_converged());
  const json good = read_json(out / "checkpoint.json");
  ASSERT_FALSE(good["integrator_state"]["multipliers"].empty());
  // 4 hexahedra, 20 vertices: keys from -60 (contact rows) to 3 (energy rows).
  for (const json& pair : {json::array({4, 1.0}), json::array({1000000000000LL, 1.0}), json::array({-61, 1.0}),
                           json::array({1.5, 1.0}), json::array({0, "1"}), json::array({0}), json(7)}) {
    SCOPED_TRACE(pair.dump());
    json bad = good;
    bad["integrator_state"]["multipliers"] = json::array({pair});
    write_json(out / "checkpoint.json", bad);
    expect_contains(error_message([&] { run(scene, out, 4, true); }),
                    {"checkpoint.json: /integrator_state/multipliers/0: "});
  }
  json bad = good;
  bad["integrator_state"].erase("multipliers");
  write_json(out / "checkpoint.json", bad);
  expect_contains(error_message([&] { run(scene, out, 4, true); }), {"checkpoint.json: /integrator_state: ", "multipliers"});
  // The extreme keys that are in range resume.
  bad = good;
  bad["integrator_state"]["multipliers"] = json::array({json::array({3, 0.001}), json::array({-60, 0.0})});
  write_json(out / "checkpoint.json", bad);
  EXPECT_EQ(run(scene, out, 4, true).frames.size(), 4u);
  // The SQP predictor and the last correction, where present, are one finite number per DOF (60
  // here).
  json wrong_entry = json::array();
  for (int i = 0; i < 60; ++i) wrong_entry.push_back(i == 7 ? json("0.1") : json(0.0));
  for (const std::string key : {"predictor", "correction"}) {
    for (const json& values : {json::array({0.0, 1.0}), json(3.0), wrong_entry}) {
      SCOPED_TRACE(key + " " + values.dump());
      bad = good;
      bad["integrator_state"][key] = values;
      write_json(out / "checkpoint.json", bad);
      expect_contains(error_message([&] { run(scene, out, 4, true); }), {"checkpoint.json: /integrator_state/" + key});
    }
    bad = good;
    bad["integrator_state"][key] = std::vector<double>(60, 0.0);
    write_json(out / "checkpoint.json", bad);
    EXPECT_EQ(run(scene, out, 4, true).frames.size(), 4u);
  }
}

TEST(Checkpoint, ResumeRefusesWhenAnyFileTheSceneReadsChanged) {
  TempDir dir;
  dir.write("hex2.mesh", test::read_file(test::data_path("hex2.mesh")));
  dir.write("surface.obj", cube_obj(0.3, 0.7));
  dir.write("bone.obj", cube_obj(0.4, 0.6));
  dir.write("rig.json", rig().dump(2));
  const auto mesh_scene = dir.write("mesh_scene.json", mesh_file_scene().dump());
  const auto rig_scene = dir.write("rig_scene.json", rigged_scene().dump());

  // Each file in turn: changed by one byte after two frames, the resume names it; put back,
  // the resume goes on.
  const std::vector<std::pair<std::filesystem::path, std::string>> cases = {
      {mesh_scene, "hex2.mesh"}, {rig_scene, "surface.obj"}, {rig_scene, "rig.json"}, {rig_scene, "bone.obj"}};
  for (const auto& entry : cases) {
    const auto& [scene, name] = entry;  // (clang 14 cannot capture a structured binding below)
    const std::filesystem::path& scene_file = scene;
    SCOPED_TRACE(name);
    const auto out = dir / ("out_" + name);
    ASSERT_TRUE(run(scene, out, 2, false).all_converged());
    const auto checkpoint = read_json(out / "checkpoint.json");
    EXPECT_TRUE(checkpoint["inputs"].contains(name)) << checkpoint["inputs"].dump();
    const std::string original = test::read_file(dir / name);
    dir.write(name, original + (name.ends_with(".json") ? " " : "\n# edited\n"));
    const std::string message = error_message([&] { run(scene_file, out, 3, true); });
    EXPECT_NE(message.find((dir / name).string() + ": changed since checkpoint"), std::string::npos) << message;
    expect_contains(message, {"checkpoint.json", "without --resume"});
    dir.write(name, original);
    EXPECT_EQ(run(scene, out, 3, true).frames.size(), 3u);
  }
}

TEST(Checkpoint, InputsAreNamedRelativeToTheScenesFolder) {
  TempDir dir;
  std::filesystem::create_directories(dir / "meshes");
  dir.write("meshes/hex2.mesh", test::read_file(test::data_path("hex2.mesh")));
  json j = mesh_file_scene();
  j["mesh"]["file"] = "meshes/hex2.mesh";
  const Scene scene = load_scene(dir.write("scene.json", j.dump()));
  const RunFingerprint f = fingerprint_run(scene);
  ASSERT_EQ(f.inputs.size(), 1u);
  EXPECT_EQ(f.inputs[0].name, "meshes/hex2.mesh");
  EXPECT_EQ(f.inputs[0].path, dir / "meshes/hex2.mesh");
  // Size and hash: one changed byte changes it, the same bytes elsewhere do not.
  const std::string bytes = test::read_file(dir / "meshes/hex2.mesh");
  EXPECT_EQ(f.inputs[0].fingerprint.substr(0, f.inputs[0].fingerprint.find(':')), std::to_string(bytes.size()));
  std::string changed = bytes;
  changed[changed.size() / 2] ^= 1;
  dir.write("meshes/hex2.mesh", changed);
  EXPECT_NE(fingerprint_run(scene).inputs[0].fingerprint, f.inputs[0].fingerprint);
  dir.write("meshes/hex2.mesh", bytes);
  EXPECT_EQ(fingerprint_run(scene).inputs[0].fingerprint, f.inputs[0].fingerprint);
}

}  // namespace
}  // namespace sinew
