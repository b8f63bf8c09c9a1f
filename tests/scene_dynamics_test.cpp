// The scene's `dynamics` section and `obstacles` list: what each field parses to, defaults,
// and that every bad value is rejected naming the file, JSON path and reason.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

using nlohmann::json;
using test::error_message;

json with(const char* patch) {
  json j = json::parse(R"({"mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}, "cells": [2, 2, 2]},
                           "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.45}})");
  j.merge_patch(json::parse(patch));
  return j;
}

TEST(SceneDynamics, FieldsAndDefaults) {
  const Scene quasi = parse_scene(with("{}"), "s.json");
  EXPECT_FALSE(quasi.dynamics.has_value());
  EXPECT_TRUE(quasi.obstacles.empty());

  const Scene d = parse_scene(with(R"({"dynamics": {"time_step": 0.01}})"), "s.json");
  ASSERT_TRUE(d.dynamics.has_value());
  EXPECT_EQ(d.dynamics->time_step, 0.01);
  EXPECT_EQ(d.dynamics->substeps, 1);
  EXPECT_EQ(d.dynamics->integrator, DynamicsScheme::BackwardEuler);
  EXPECT_EQ(d.dynamics->mass, MassKind::Lumped);
  EXPECT_EQ(d.dynamics->rayleigh_alpha, 0.0);
  EXPECT_EQ(d.dynamics->rayleigh_beta, 0.0);
  EXPECT_EQ(d.dynamics->initial_velocity, Eigen::Vector3d::Zero());
  EXPECT_EQ(d.dynamics->friction_velocity, 1e-2);

  const Scene all = parse_scene(with(R"({"dynamics": {"time_step": 0.04, "substeps": 4, "integrator": "semi_implicit",
      "mass": "consistent", "rayleigh": {"alpha": 0.5, "beta": 0.01}, "initial_velocity": [1, 2, 3],
      "friction_velocity": 0.001},
    "obstacles": [
      {"type": "plane", "point": [0, 0, -1], "normal": [0, 0, 2], "stiffness": 1e6, "friction": 0.4},
      {"name": "ball", "type": "sphere", "center": [0, 0, 3], "radius": 0.5, "stiffness": 2e6,
       "motion": {"type": "translate", "per_frame": [0, 0, -0.1]}},
      {"type": "capsule", "a": [0, 0, 0], "b": [1, 0, 0], "radius": 0.1, "stiffness": 1e6},
      {"type": "cylinder", "center": [0, 0, 0], "axis": [1, 0, 0], "radius": 0.1, "length": 2, "stiffness": 1e6},
      {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "stiffness": 1e6}]})"),
                                "s.json");
  EXPECT_EQ(all.dynamics->substeps, 4);
  EXPECT_EQ(all.dynamics->integrator, DynamicsScheme::SemiImplicit);
  EXPECT_EQ(all.dynamics->mass, MassKind::Consistent);
  EXPECT_EQ(all.dynamics->rayleigh_alpha, 0.5);
  EXPECT_EQ(all.dynamics->rayleigh_beta, 0.01);
  EXPECT_EQ(all.dynamics->initial_velocity, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(all.dynamics->friction_velocity, 0.001);
  ASSERT_EQ(all.obstacles.size(), 5u);
  const char* types[] = {"plane", "sphere", "capsule", "cylinder", "box"};
  for (int i = 0; i < 5; ++i) EXPECT_EQ(all.obstacles[i].shape->type(), types[i]);
  EXPECT_EQ(all.obstacles[0].name, "/obstacles/0");
  EXPECT_EQ(all.obstacles[0].contact.friction, 0.4);
  EXPECT_EQ(all.obstacles[1].name, "ball");
  EXPECT_EQ(all.obstacles[1].contact.stiffness, 2e6);
  EXPECT_TRUE(std::holds_alternative<Translation>(all.obstacles[1].motion));
  EXPECT_NEAR(all.obstacles[0].shape->query(Eigen::Vector3d(5, 5, 0)).distance, 1.0, 1e-15);  // normal normalised
}

struct BadDynamics {
  const char* patch;
  const char* expected;  // after "dir/scene.json: "
};
class SceneDynamicsValidation : public ::testing::TestWithParam<BadDynamics> {};

TEST_P(SceneDynamicsValidation, NamesFilePathAndReason) {
  const std::string message = error_message([&] { parse_scene(with(GetParam().patch), "dir/scene.json"); });
  const std::string expected = std::string("dir/scene.json: ") + GetParam().expected;
  EXPECT_EQ(message.rfind(expected, 0), 0u) << "got: " << message << "\nexpected to start with: " << expected;
}

INSTANTIATE_TEST_SUITE_P(
    Scene, SceneDynamicsValidation,
    ::testing::Values(
        BadDynamics{R"({"dynamics": {}})", "/dynamics/time_step: required field is missing"},
        BadDynamics{R"({"dynamics": {"time_step": 0.1}, "solver": {"predictor": "none"}})",
                    "/solver/predictor: applies to quasistatic runs only"},
        BadDynamics{R"({"dynamics": {"time_step": 0}})", "/dynamics/time_step: must be a positive"},
        BadDynamics{R"({"dynamics": {"time_step": -1}})", "/dynamics/time_step: must be a positive"},
        BadDynamics{R"({"dynamics": {"time_step": "0.1"}})", "/dynamics/time_step: must be a"},
        BadDynamics{R"({"dynamics": {"time_step": 0.1, "dt": 1}})", "/dynamics/dt: unknown field"},
        BadDynamics{R"({"dynamics": {"time_step": 0.1, "substeps": 0}})", "/dynamics/substeps: must be"},
        BadDynamics{R"({"dynamics": {"time_step": 0.1, "substeps": 2.5}})", "/dynamics/substeps: must be an integer"},
        BadDynamics{R"({"dynamics": {"time_step": 0.1, "substeps": 1000000}})", "/dynamics/substeps: must be at most"},
        BadDynamics{R"({"dynamics": {"time_step": 0.1, "integrator": "rk4"}})", "/dynamics/integrator: unknown value 'rk4'"},
        BadDynamics{R"({"dynamics": {"time_step": 0.1, "mass": "diagonal"}})", "/dynamics/mass: unknown value"},
        BadDynamics{R"({"dynamics": {"time_step": 0.1, "rayleigh": {"alpha": -1}}})", "/dynamics/rayleigh/alpha: must be >= 0"},
        BadDynamics{R"({"dynamics": {"time_step": 0.1, "rayleigh": {"beta": -1}}})", "/dynamics/rayleigh/beta: must be >= 0"},
        BadDynamics{R"({"dynamics": {"time_step": 0.1, "rayleigh": {"gamma": 1}}})", "/dynamics/rayleigh/gamma: unknown field"},
        BadDynamics{R"({"dynamics": {"time_step": 0.1, "initial_velocity": [0, 0]}})", "/dynamics/initial_velocity: must be an array of 3"},
        BadDynamics{R"({"dynamics": {"time_step": 0.1, "friction_velocity": 0}})", "/dynamics/friction_velocity: must be a positive"},
        BadDynamics{R"({"dynamics": 3})", "/dynamics: must be an object"},
        BadDynamics{R"({"obstacles": {}})", "/obstacles: must be an array"},
        BadDynamics{R"({"obstacles": [{"stiffness": 1}]})", "/obstacles/0/type: missing"},
        BadDynamics{R"({"obstacles": [{"type": "torus", "stiffness": 1}]})", "/obstacles/0/type: unknown value 'torus'"},
        BadDynamics{R"({"obstacles": [{"type": "plane", "point": [0,0,0], "normal": [0,0,1]}]})", "/obstacles/0/stiffness: required field is missing"},
        BadDynamics{R"({"obstacles": [{"type": "plane", "point": [0,0,0], "normal": [0,0,0], "stiffness": 1}]})", "/obstacles/0/normal: must be non-zero"},
        BadDynamics{R"({"obstacles": [{"type": "plane", "point": [0,0,0], "normal": [0,0,1], "stiffness": -1}]})", "/obstacles/0/stiffness: must be a positive"},
        BadDynamics{R"({"obstacles": [{"type": "plane", "point": [0,0,0], "normal": [0,0,1], "stiffness": 1, "friction": -0.1}]})", "/obstacles/0/friction: must be >= 0"},
        BadDynamics{R"({"obstacles": [{"type": "plane", "point": [0,0,0], "normal": [0,0,1], "stiffness": 1, "friction": 0.1}]})", "/obstacles/0/friction: friction needs a `dynamics` section"},
        BadDynamics{R"({"obstacles": [{"type": "plane", "point": [0,0,0], "normal": [0,0,1], "stiffness": 1, "radius": 1}]})", "/obstacles/0/radius: unknown field"},
        BadDynamics{R"({"obstacles": [{"type": "sphere", "center": [0,0,0], "radius": 0, "stiffness": 1}]})", "/obstacles/0/radius: must be a positive"},
        BadDynamics{R"({"obstacles": [{"type": "capsule", "a": [0,0,0], "b": [0,0,0], "radius": 1, "stiffness": 1}]})", "/obstacles/0/b: must differ from a"},
        BadDynamics{R"({"obstacles": [{"type": "cylinder", "center": [0,0,0], "axis": [0,0,1], "radius": 1, "stiffness": 1}]})", "/obstacles/0/length: required field is missing"},
        BadDynamics{R"({"obstacles": [{"type": "box", "min": [0,0,0], "max": [1,0,1], "stiffness": 1}]})", "/obstacles/0/max: must exceed min"},
        BadDynamics{R"({"obstacles": [{"type": "sphere", "center": [0,0,0], "radius": 1, "stiffness": 1, "motion": {"type": "spin"}}]})", "/obstacles/0/motion/type: unknown value 'spin'"},
        BadDynamics{R"({"obstacles": [{"type": "sphere", "center": [0,0,0], "radius": 1, "stiffness": 1, "motion": {"type": "keyframes", "keys": [{"frame": 2}, {"frame": 1}]}}]})", "/obstacles/0/motion/keys/1/frame: must be after the previous keyframe's"}));

TEST(SceneDynamics, CheckpointResumeContinuesWithVelocities) {
  // A resumed dynamic run must restore velocities, not restart from rest: frames 1-6 in one
  // go and frames 1-3 then --resume to 6 end in the same state.
  test::TempDir dir;
  json j = with(R"({"loads": {"gravity": [0, 0, -9.81]}, "dynamics": {"time_step": 0.02},
                   "obstacles": [{"type": "plane", "point": [0, 0, -0.05], "normal": [0, 0, 1], "stiffness": 1e7}]})");
  j["mesh"]["cells"] = {1, 1, 1};
  const auto file = dir.write("fall.json", j.dump());
  const Scene scene = load_scene(file);
  RunOptions once;
  once.frames = 6;
  const RunSummary whole = run_scene(scene, once);
  RunOptions first;
  first.out_dir = dir.path() / "out";
  first.frames = 3;
  run_scene(scene, first);
  RunOptions rest = first;
  rest.frames = 6;
  rest.resume = true;
  const RunSummary resumed = run_scene(scene, rest);
  ASSERT_TRUE(whole.all_converged() && resumed.all_converged());
  EXPECT_LT((whole.x - resumed.x).norm(), 1e-9);
  EXPECT_GT(whole.frames.back().contacts, 0);       // it reached the plane
  EXPECT_GT(whole.frames[2].kinetic_energy, 0.0);  // and was moving at frame 3
}

TEST(SceneDynamics, KinematicBoundaryMotionIsFollowedInDynamics) {
  // A column whose top is moved sideways by a boundary motion: the constrained vertices sit
  // exactly on the motion at every frame end, and the free ones lag behind (inertia).
  test::TempDir dir;
  json j = with(R"({"boundary": [{"name": "top", "select": {"plane": {"point": [0, 0, 1], "normal": [0, 0, 1]}},
                                  "motion": {"type": "translate", "per_frame": [0.02, 0, 0]}}],
                   "dynamics": {"time_step": 0.01, "substeps": 2, "mass": "consistent"}, "frames": 3})");
  const Scene scene = load_scene(dir.write("column.json", j.dump()));
  const RunSummary s = run_scene(scene, {});
  ASSERT_TRUE(s.all_converged());
  const VolumeMesh mesh = build_scene_mesh(scene);
  double free_max = 0.0;
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) {
    const double rest_x = mesh.vertices(v, 0);
    if (mesh.vertices(v, 2) == 1.0) {
      EXPECT_NEAR(s.x(3 * v), rest_x + 0.06, 1e-12);
    } else {
      free_max = std::max(free_max, s.x(3 * v) - rest_x);
    }
  }
  EXPECT_LT(free_max, 0.06);
  EXPECT_GT(s.frames.back().kinetic_energy, 0.0);
  EXPECT_NE(s.frames.back().reactions[0], Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace sinew
