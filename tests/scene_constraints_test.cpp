// The "constraints" scene section: strict parsing and the constrained-dynamics run's summary.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/run/simulation.hpp"

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
    "dynamics": {"time_step": 0.02, "substeps": 2},
    "constraints": {"energy_limit": {"max_energy": 0.002}},
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
  EXPECT_EQ(c.step.time_step, 0.01);  // dynamics.time_step / substeps
  ASSERT_TRUE(c.step.energy_limit.has_value());
  EXPECT_EQ(c.step.energy_limit->max_energy, 0.002);
  EXPECT_EQ(c.step.energy_limit->jacobian, JacobianKind::Exact);
  EXPECT_EQ(c.contact_margin, 0.01);
  EXPECT_TRUE(c.step.reuse.enabled);
  EXPECT_FALSE(parse_scene(patched({{"constraints", nullptr}}), "s.json").constraints.has_value());
  const Scene t = parse_scene(
      patched({{"constraints",
                {{"factorization",
                  {{"reuse", false}, {"max_cg_iterations", 5}, {"cg_tolerance", 1e-9}, {"column_reuse_tolerance", 0}}}}}}),
      "s.json");
  EXPECT_FALSE(t.constraints->step.reuse.enabled);
  EXPECT_EQ(t.constraints->step.reuse.max_cg_iterations, 5);
  EXPECT_EQ(t.constraints->step.reuse.cg_tolerance, 1e-9);
  EXPECT_EQ(t.constraints->step.reuse.column_reuse_tolerance, 0.0);
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
  expect_contains(parse_error(patched({{"constraints", {{"contact", {{"margin", -0.1}}}}}})),
                  {"/constraints/contact/margin", "non-negative"});
  expect_contains(parse_error(patched({{"constraints", {{"contact", {{"tolerance", 0}}}}}})),
                  {"/constraints/contact/tolerance", "positive"});
  expect_contains(parse_error(patched({{"constraints", {{"pgs", {{"iterations", 0}}}}}})), {"/constraints/pgs/iterations"});
  expect_contains(parse_error(patched({{"constraints", {{"sqp", {{"tolerance", 1}}}}}})), {"/constraints/sqp/tolerance"});
  expect_contains(parse_error(patched({{"constraints", {{"energy_limit", {{"activation", 2}}}}}})),
                  {"/constraints/energy_limit/activation", "[0, 1]"});
  expect_contains(parse_error(patched({{"constraints", {{"factorization", {{"reuse", "yes"}}}}}})),
                  {"/constraints/factorization/reuse"});
  expect_contains(parse_error(patched({{"constraints", {{"factorization", {{"max_cg_iterations", 0}}}}}})),
                  {"/constraints/factorization/max_cg_iterations"});
  expect_contains(parse_error(patched({{"constraints", {{"factorization", {{"cg_tolerance", 2}}}}}})),
                  {"/constraints/factorization/cg_tolerance", "below 1"});
  expect_contains(parse_error(patched({{"constraints", {{"factorization", {{"column_reuse_tolerance", -1}}}}}})),
                  {"/constraints/factorization/column_reuse_tolerance", "[0, 1)"});
  expect_contains(parse_error(patched({{"constraints", {{"factorization", {{"refactor_every", 3}}}}}})),
                  {"/constraints/factorization/refactor_every"});
}

TEST(SceneConstraints, OneConfigFormatTimeSteppingFromDynamicsContactFromObstacles) {
  // Keys that moved out of `constraints` name their new place.
  expect_contains(parse_error(patched({{"constraints", {{"time_step", 0.01}}}})),
                  {"dir/scene.json: /constraints/time_step", "dynamics.time_step"});
  expect_contains(parse_error(patched({{"constraints", {{"steps_per_frame", 2}}}})),
                  {"/constraints/steps_per_frame", "dynamics.substeps"});
  expect_contains(parse_error(patched({{"constraints", {{"initial_velocity", {0, 0, 1}}}}})),
                  {"/constraints/initial_velocity", "dynamics.initial_velocity"});
  expect_contains(parse_error(patched({{"constraints", {{"contact", {{"ground", json::object()}}}}}})),
                  {"/constraints/contact/ground", "obstacles", "plane"});
  expect_contains(parse_error(patched({{"constraints", {{"contact", {{"friction", 0.5}}}}}})),
                  {"/constraints/contact/friction", "obstacle"});
  // A constrained scene needs `dynamics`, and only what its stepper does.
  expect_contains(parse_error(patched({{"dynamics", nullptr}})), {"dir/scene.json: /constraints", "dynamics"});
  expect_contains(parse_error(patched({{"dynamics", {{"integrator", "semi_implicit"}}}})),
                  {"dir/scene.json: /dynamics/integrator", "backward_euler"});
  expect_contains(parse_error(patched({{"dynamics", {{"mass", "consistent"}}}})), {"/dynamics/mass", "lumped"});
  expect_contains(parse_error(patched({{"dynamics", {{"rayleigh", {{"alpha", 1}}}}}})), {"/dynamics/rayleigh"});
  expect_contains(parse_error(patched({{"dynamics", {{"friction_velocity", 0.1}}}})), {"/dynamics/friction_velocity", "penalty"});
  const json ground = {{"type", "plane"}, {"point", {0, 0, -0.2}}, {"normal", {0, 0, 1}}, {"friction", 0.3}};
  json with_stiffness = ground;
  with_stiffness["stiffness"] = 1e6;
  expect_contains(parse_error(patched({{"obstacles", {ground, with_stiffness}}})), {"/obstacles/1/stiffness", "penalty"});
  // Accepted: explicit backward Euler and lumped mass, obstacles without stiffness.
  const Scene s = parse_scene(
      patched({{"dynamics", {{"time_step", 0.03}, {"substeps", 3}, {"integrator", "backward_euler"}, {"mass", "lumped"},
                             {"initial_velocity", {1, 0, 0}}}},
               {"obstacles", {ground}}}),
      "dir/scene.json");
  EXPECT_DOUBLE_EQ(s.constraints->step.time_step, 0.01);
  ASSERT_EQ(s.obstacles.size(), 1u);
  EXPECT_EQ(s.obstacles[0].contact.friction, 0.3);
}

TEST(SceneConstraints, ObstaclesStopTheConstrainedBody) {
  // The free end of the cantilever (initially moving down at 1 m/s) lands on a static box obstacle
  // 3 cm below it, and a rising keyframed sphere pushes its middle; neither is penetrated.
  test::TempDir dir;
  const auto file = dir.path() / "scene.json";
  json j = beam_scene();
  j.erase("constraints");
  j["constraints"] = {{"contact", {{"margin", 0.02}, {"tolerance", 1e-4}}}};
  j["dynamics"] = {{"time_step", 0.02}, {"substeps", 2}, {"initial_velocity", {0, 0, -1}}};
  j["obstacles"] = json::parse(R"([
    {"name": "shelf", "type": "box", "min": [0.3, -0.2, -0.3], "max": [0.5, 0.2, -0.08], "friction": 0.5},
    {"name": "pusher", "type": "sphere", "center": [0.2, 0, -0.25], "radius": 0.1, "friction": 0.2,
     "motion": {"type": "keyframes", "keys": [{"frame": 0}, {"frame": 10, "translation": [0, 0, 0.1]}]}}
  ])");
  j["frames"] = 12;
  std::ofstream(file) << j.dump();
  RunOptions options;
  options.out_dir = dir.path() / "out";
  const RunSummary summary = run_scene(load_scene(file), options);
  EXPECT_TRUE(summary.all_converged());
  const json s = json::parse(std::ifstream(options.out_dir / "summary.json"));
  int contacts = 0;
  for (const auto& frame : s["frames"]) {
    const json& f = frame["counters"];  // the energy-limited integrator's named counters
    EXPECT_LE(f["max_penetration"].get<double>(), 1e-4);
    contacts = std::max(contacts, f["max_active_contacts"].get<int>());
  }
  EXPECT_GT(contacts, 0);
  // Independently: no vertex of the final state is inside the shelf.
  for (Eigen::Index v = 0; v < summary.x.size() / 3; ++v) {
    const Eigen::Vector3d p = summary.x.segment<3>(3 * v);
    const bool inside = p.x() > 0.3 + 1e-4 && p.x() < 0.5 - 1e-4 && std::abs(p.y()) < 0.2 - 1e-4 && p.z() < -0.08 - 1e-4;
    EXPECT_FALSE(inside) << "vertex " << v << " at " << p.transpose();
  }
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
  EXPECT_EQ(s["integrator"], "energy_limited");
  for (const auto& frame : s["frames"]) {
    const json& f = frame["counters"];  // the energy-limited integrator's named counters
    for (const char* key : {"sqp_iterations", "pgs_iterations", "max_energy_violation", "max_penetration",
                            "max_active_energy_constraints", "max_active_contacts", "max_pgs_residual"})
      EXPECT_TRUE(f.contains(key)) << key;
    EXPECT_LE(f["max_element_energy"].get<double>(), 0.002 * (1 + 1e-3));
    sqp += f["sqp_iterations"].get<int>();
  }
  EXPECT_EQ(s["total_counters"]["sqp_iterations"].get<int>(), sqp);
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
  EXPECT_GT(last["counters"]["max_energy_violation"].get<double>(), 1e-9);
  expect_contains(last["failure"].get<std::string>(), {"SQP stopped after 1 iteration", "energy violation"});
}

TEST(SceneConstraints, MovingBoundaryDrivesTheBody) {
  // The wall rises 1 cm per frame: its vertices are where the motion puts them at every frame's
  // end, and the free end of the beam follows (energy-limited dynamics takes any boundary motion).
  test::TempDir dir;
  const auto file = dir.path() / "scene.json";
  json j = beam_scene();
  j["boundary"][0]["motion"] = {{"type", "translate"}, {"per_frame", {0, 0, 0.01}}};
  j["loads"] = json::object();
  std::ofstream(file) << j.dump();
  const Scene scene = load_scene(file);
  const RunSummary s = run_scene(scene, {});
  ASSERT_TRUE(s.all_converged());
  const VolumeMesh mesh = build_scene_mesh(scene);
  double tip = 0.0;
  int wall = 0, tip_vertices = 0;
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::Vector3d X = mesh.vertices.row(v).transpose(), x = s.x.segment<3>(3 * v);
    if (X.x() <= 1e-9) {
      EXPECT_LT((x - X - Eigen::Vector3d(0, 0, 0.03)).norm(), 1e-12) << "wall vertex " << v;
      ++wall;
    } else if (X.x() >= 0.4 - 1e-9) {
      tip += x.z() - X.z();
      ++tip_vertices;
    }
  }
  EXPECT_EQ(wall, 4);
  EXPECT_GT(tip / tip_vertices, 0.005);  // lifted with the wall
}

TEST(SceneConstraints, ResumeContinuesFromTheCheckpointToTheSameMotion) {
  // 6 frames in one go against 3 frames and --resume to 6, with the energy limit active. The
  // lagged factorisations are rebuilt after a resume, so the states agree to the solver
  // tolerances rather than bit for bit.
  test::TempDir dir;
  const auto file = dir.path() / "scene.json";
  json j = beam_scene();
  j["frames"] = 6;
  std::ofstream(file) << j.dump();
  const Scene scene = load_scene(file);
  RunOptions whole_options;
  whole_options.out_dir = dir.path() / "whole";
  const RunSummary whole = run_scene(scene, whole_options);
  RunOptions part = whole_options;
  part.out_dir = dir.path() / "resumed";
  part.frames = 3;
  const RunSummary first = run_scene(scene, part);
  ASSERT_EQ(first.frames.size(), 3u);
  EXPECT_TRUE(std::filesystem::exists(part.out_dir / "checkpoint.json"));
  part.frames = 6;
  part.resume = true;
  const RunSummary resumed = run_scene(scene, part);
  ASSERT_TRUE(whole.all_converged() && resumed.all_converged());
  ASSERT_EQ(resumed.frames.size(), 6u);
  EXPECT_LT((whole.x - resumed.x).cwiseAbs().maxCoeff(), 1e-6);  // metres, on a 0.4 m beam
  // The checkpoint keeps the multipliers and the SQP predictor: the resumed frames take the
  // uninterrupted run's SQP iterations and end with its constraint errors (without the predictor
  // the first resumed step starts elsewhere: same SQP counts here, frame 4's largest energy
  // violation 1.5e-4 instead of 7.2e-4).
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(resumed.frames[i].counter("sqp_iterations"), whole.frames[i].counter("sqp_iterations")) << i;
    EXPECT_NEAR(resumed.frames[i].residual, whole.frames[i].residual, 1e-7) << i;
  }
  const json s = json::parse(std::ifstream(part.out_dir / "summary.json"));
  EXPECT_EQ(s["frames_completed"], 6);
  EXPECT_EQ(s["frames"].size(), 6u);
  EXPECT_TRUE(std::filesystem::exists(part.out_dir / "frame_0006.vtu"));
  // The resumed simulation.pvd lists the frames of both parts, as the uninterrupted one does.
  EXPECT_EQ(test::read_file(whole_options.out_dir / "simulation.pvd"), test::read_file(part.out_dir / "simulation.pvd"));

  // Refused: a changed scene, no checkpoint, a checkpoint of another kind of run.
  j["frames"] = 7;
  std::ofstream(file) << j.dump();
  expect_contains(error_message([&] { run_scene(load_scene(file), part); }), {"checkpoint.json", "scene file changed"});
  RunOptions empty = part;
  empty.out_dir = dir.path() / "nothing";
  expect_contains(error_message([&] { run_scene(load_scene(file), empty); }), {"checkpoint.json", "no checkpoint"});
  std::ofstream(part.out_dir / "checkpoint.json") << R"({"scene_fingerprint": "x", "frame": 1})";
  expect_contains(error_message([&] { run_scene(load_scene(file), part); }), {"checkpoint.json", "constrained"});
  std::ofstream(part.out_dir / "checkpoint.json") << R"({"mode": "constrained", "frame": )";
  expect_contains(error_message([&] { run_scene(load_scene(file), part); }), {"checkpoint.json", "malformed JSON"});
}

TEST(SceneConstraints, SelfContactIsIntegratedNotIgnored) {
  // Self-contact is one more form of the potential energy: the energy-limited run takes it and
  // reports its figures; the limit still holds.
  test::TempDir dir;
  const auto file = dir.path() / "scene.json";
  json j = beam_scene();
  j["self_contact"] = {{"stiffness", 1e4}};
  std::ofstream(file) << j.dump();
  RunOptions options;
  options.out_dir = dir.path() / "out";
  const RunSummary summary = run_scene(load_scene(file), options);
  ASSERT_TRUE(summary.all_converged());
  const json s = json::parse(std::ifstream(options.out_dir / "summary.json"));
  for (const auto& f : s["frames"]) {
    EXPECT_TRUE(f.contains("self_contacts"));
    EXPECT_LE(f["counters"]["max_element_energy"].get<double>(), 0.002 * (1 + 1e-3));
  }
}

}  // namespace
}  // namespace sinew

namespace sinew {
namespace {

TEST(SceneConstraints, BonesDriveEnergyLimitedDynamics) {
  // A bar held by a still bone at its left end, its right end carried 0.1 m along x by a keyed
  // bone: with a constraints section the bound vertices follow their bones at every step's end.
  test::TempDir dir;
  const auto file = dir.path() / "scene.json";
  std::ofstream(file) << R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.2, 0.2]}, "cells": [10, 2, 2]},
    "material": {"family": "linear_corotational", "E": 1e4, "nu": 0.3},
    "rig": {"bones": [
      {"name": "left", "capsule": {"a": [0, 0.1, 0.1], "b": [0.2, 0.1, 0.1], "radius": 0.15}, "keys": [{"frame": 0}]},
      {"name": "right", "capsule": {"a": [0.8, 0.1, 0.1], "b": [1, 0.1, 0.1], "radius": 0.15},
       "keys": [{"frame": 0}, {"frame": 2, "translation": [0.1, 0, 0]}]}]},
    "dynamics": {"time_step": 0.02, "substeps": 2},
    "constraints": {"energy_limit": {"max_energy": 1.0}},
    "frames": 2
  })";
  const RunSummary r = run_scene(load_scene(file), RunOptions{});
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_TRUE(r.all_converged());
  EXPECT_NEAR(r.x.reshaped(3, r.x.size() / 3).row(0).maxCoeff(), 1.1, 1e-9);  // the right end went with its bone
  EXPECT_NEAR(r.x.reshaped(3, r.x.size() / 3).row(0).minCoeff(), 0.0, 1e-9);  // the left end stayed
}

}  // namespace
}  // namespace sinew
