// The "constraints" scene section: strict parsing and the constrained-dynamics run's summary.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "sinew/scene/scene.hpp"
#include "sinew/scene/simulation.hpp"

namespace sinew {
namespace {

using nlohmann::json;
using test::error_message;
using test::expect_contains;

// A 4-hexahedron cantilever under gravity with an energy limit, 3 frames of 2 steps.
json beam_scene() {
  return json::parse(R"({
    "mesh": {"box": {"min": [0, -0.05, -0.05], "max": [0.4, 0.05, 0.05]}, "cells": [4, 1, 1]},
    "material": {"family": "linear_corotational", "E": 1e5, "nu": 0.3},
    "density": 500,
    "boundary": [{"name": "wall", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}}],
    "loads": {"gravity": [0, 0, -9.81]},
    "constraints": {"time_step": 0.01, "steps_per_frame": 2, "energy_limit": {"max_energy": 0.002}},
    "frames": 3
  })");
}

std::string parse_error(const json& j) {
  return error_message([&] { parse_scene(j, "dir/scene.json"); });
}

json patched(const json& patch) {
  json j = beam_scene();
  j.merge_patch(patch);
  return j;
}

TEST(SceneConstraints, DefaultsAndValues) {
  const Scene s = parse_scene(beam_scene(), "dir/scene.json");
  ASSERT_TRUE(s.constraints.has_value());
  const ConstraintsSpec& c = *s.constraints;
  EXPECT_EQ(c.model, "corotational");
  EXPECT_EQ(c.steps_per_frame, 2);
  EXPECT_EQ(c.step.time_step, 0.01);
  ASSERT_TRUE(c.step.energy_limit.has_value());
  EXPECT_EQ(c.step.energy_limit->max_energy, 0.002);
  EXPECT_EQ(c.step.energy_limit->jacobian, JacobianKind::Exact);
  EXPECT_FALSE(c.ground.has_value());
  EXPECT_FALSE(parse_scene(patched({{"constraints", nullptr}}), "s.json").constraints.has_value());
}

TEST(SceneConstraints, BadInputIsRejectedWithFileAndPath) {
  expect_contains(parse_error(patched({{"constraints", {{"energy_limt", 1}}}})),
                  {"dir/scene.json", "/constraints/energy_limt"});
  expect_contains(parse_error(patched({{"constraints", {{"energy_limit", {{"max_energy", -1}}}}}})),
                  {"dir/scene.json: /constraints/energy_limit/max_energy", "positive"});
  expect_contains(parse_error(patched({{"constraints", {{"energy_limit", {{"max_energy", "a lot"}}}}}})),
                  {"/constraints/energy_limit/max_energy"});
  expect_contains(parse_error(patched({{"constraints", {{"energy_limit", {{"jacobian", "numeric"}}}}}})),
                  {"/constraints/energy_limit/jacobian"});
  expect_contains(parse_error(patched({{"constraints", {{"model", "material"}, {"energy_limit", {{"jacobian", "warped"}}}}}})),
                  {"/constraints/energy_limit/jacobian", "corotational"});
  expect_contains(parse_error(patched({{"constraints", {{"time_step", 0}}}})), {"/constraints/time_step"});
  expect_contains(parse_error(patched({{"constraints", {{"steps_per_frame", 0}}}})), {"/constraints/steps_per_frame"});
  expect_contains(parse_error(patched({{"constraints", {{"contact", {{"friction", 0.5}}}}}})),
                  {"/constraints/contact/ground", "missing"});
  expect_contains(parse_error(patched({{"constraints", {{"contact", {{"ground", json::object()}, {"friction", -0.5}}}}}})),
                  {"/constraints/contact/friction", "non-negative"});
  expect_contains(parse_error(patched({{"constraints", {{"contact", {{"ground", {{"normal", {0, 0, 0}}}}}}}}})),
                  {"/constraints/contact/ground/normal", "non-zero"});
  expect_contains(parse_error(patched({{"constraints", {{"pgs", {{"iterations", 0}}}}}})), {"/constraints/pgs/iterations"});
  expect_contains(parse_error(patched({{"constraints", {{"sqp", {{"tolerance", 1}}}}}})), {"/constraints/sqp/tolerance"});
  expect_contains(parse_error(patched({{"constraints", {{"energy_limit", {{"activation", 2}}}}}})),
                  {"/constraints/energy_limit/activation", "[0, 1]"});
}

TEST(SceneConstraints, RunWritesPerFrameSolverFiguresAndHoldsTheLimit) {
  test::TempDir dir;
  const auto file = dir.path() / "scene.json";
  std::ofstream(file) << beam_scene().dump();
  RunOptions options;
  options.out_dir = dir.path() / "out";
  std::filesystem::create_directories(options.out_dir);
  std::ofstream(options.out_dir / "frame_0042.vtu") << "from an earlier, longer run";
  const RunSummary summary = run_scene(load_scene(file), options);
  EXPECT_FALSE(std::filesystem::exists(options.out_dir / "frame_0042.vtu"));  // a fresh run replaces old outputs
  ASSERT_EQ(summary.frames.size(), 3u);
  EXPECT_TRUE(summary.all_converged());
  const json s = json::parse(std::ifstream(options.out_dir / "summary.json"));
  EXPECT_EQ(s["frames_completed"], 3);
  EXPECT_TRUE(s["all_converged"].get<bool>());
  int sqp = 0;
  for (const auto& f : s["frames"]) {
    for (const char* key : {"sqp_iterations", "pgs_iterations", "max_energy_violation", "max_penetration",
                            "max_active_energy_constraints", "max_active_contacts", "max_pgs_residual"})
      EXPECT_TRUE(f.contains(key)) << key;
    EXPECT_LE(f["max_element_energy"].get<double>(), 0.002 * (1 + 1e-3));
    sqp += f["sqp_iterations"].get<int>();
  }
  EXPECT_GT(sqp, 0);  // the limit was reached and enforced
  EXPECT_TRUE(std::filesystem::exists(options.out_dir / "frame_0003.vtu"));
}

TEST(SceneConstraints, UnconvergedSqpIsReportedNotHidden) {
  // One SQP iteration cannot bring a quadratic energy back onto a tight limit within 1e-9.
  test::TempDir dir;
  const auto file = dir.path() / "scene.json";
  std::ofstream(file) << patched({{"constraints", {{"energy_limit", {{"max_energy", 0.0005}, {"tolerance", 1e-9}}},
                                                   {"sqp", {{"iterations", 1}}}}}})
                             .dump();
  RunOptions options;
  options.out_dir = dir.path() / "out";
  const RunSummary summary = run_scene(load_scene(file), options);
  EXPECT_FALSE(summary.all_converged());
  const json s = json::parse(std::ifstream(options.out_dir / "summary.json"));
  EXPECT_FALSE(s["all_converged"].get<bool>());
  const json& last = s["frames"].back();
  EXPECT_FALSE(last["converged"].get<bool>());
  EXPECT_GT(last["max_energy_violation"].get<double>(), 1e-9);
  expect_contains(last["failure"].get<std::string>(), {"SQP stopped after 1 iteration", "energy violation"});
}

TEST(SceneConstraints, NonPinnedBoundaryAndResumeAreRefused) {
  test::TempDir dir;
  const auto file = dir.path() / "scene.json";
  json j = beam_scene();
  j["boundary"][0]["motion"] = {{"type", "translate"}, {"per_frame", {0.1, 0, 0}}};
  std::ofstream(file) << j.dump();
  expect_contains(error_message([&] { run_scene(load_scene(file), {}); }), {"/boundary/0/motion", "pinned"});
  RunOptions options;
  options.out_dir = dir.path() / "out";
  options.resume = true;
  std::ofstream(file) << beam_scene().dump();
  expect_contains(error_message([&] { run_scene(load_scene(file), options); }), {"--resume"});
}

}  // namespace
}  // namespace sinew
