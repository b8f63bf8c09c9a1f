// Bones: capsule shapes, keyframe interpolation, binding, the spring form's derivatives, the
// strict rig reader, and a solve driven by noisy intersecting bones.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>
#include <nlohmann/json.hpp>
#include <random>

#include "dynamics_test_support.hpp"
#include "sinew/core/error.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/material/spec.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/forms/bone_spring_form.hpp"
#include "sinew/model/rig_reader.hpp"
#include "experiments/elbow_experiment.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/run/simulation.hpp"
#include "sinew/solver/newton.hpp"

namespace sinew {
namespace {

Bone capsule_bone(const std::string& name, Eigen::Vector3d a, Eigen::Vector3d b, double r) {
  Bone bone;
  bone.name = name;
  bone.shape = std::make_shared<CapsuleShape>(a, b, r);
  bone.keys.push_back(BoneKey{});
  return bone;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(RigCapsule, ContainsPointsWithinRadiusOfTheSegment) {
  const CapsuleShape c(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), 0.1);
  EXPECT_TRUE(c.contains(Eigen::Vector3d(0.5, 0.09, 0)));
  EXPECT_FALSE(c.contains(Eigen::Vector3d(0.5, 0.11, 0)));
  EXPECT_TRUE(c.contains(Eigen::Vector3d(1.05, 0.05, 0)));  // rounded cap
  EXPECT_FALSE(c.contains(Eigen::Vector3d(1.08, 0.08, 0)));
  EXPECT_THROW(CapsuleShape(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), -1.0), Error);
}

TEST(RigKeys, RigidKeysSlerpRotationAndLerpTranslation) {
  Bone bone = capsule_bone("b", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.1);
  BoneKey k1;
  k1.frame = 10.0;
  k1.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()));
  k1.translation = Eigen::Vector3d(2, 0, 0);
  bone.keys.push_back(k1);
  const Affine34 mid = bone.transform_at(5.0);
  const Mat3 R45 = Eigen::AngleAxisd(std::numbers::pi / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_LE((mid.leftCols<3>() - R45).norm(), 1e-12);
  EXPECT_LE((mid.col(3) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-12);
  // Held outside the keyed range.
  EXPECT_LE((bone.transform_at(-3.0) - Affine34::Identity()).norm(), 1e-12);
  EXPECT_LE((bone.transform_at(99.0).col(3) - k1.translation).norm(), 1e-12);
}

TEST(Rig, TurnAboutAPivotKeepsThePivotBetweenFarApartKeys) {
  // A rest key, then 120 degrees about an elbow 0.3 m from the origin in one span: half-way the
  // bone has turned 60 degrees about the elbow, which has not moved.
  const nlohmann::json j = nlohmann::json::parse(R"({"bones": [
      {"name": "forearm", "capsule": {"a": [0.4, 0, 0], "b": [0.55, 0, 0], "radius": 0.02},
       "keys": [{"frame": 0},
                {"frame": 4, "rotation": {"axis": [0, -1, 0], "degrees": 120, "center": [0.3, 0, 0.05]}}]}]})");
  const Rig rig = parse_rig(j, "rig.json");
  const Eigen::Vector3d elbow(0.3, 0, 0.05), wrist(0.55, 0, 0.05);
  for (double frame : {0.0, 1.0, 2.0, 3.0, 4.0}) {
    const Affine34 A = rig.bones[0].transform_at(frame);
    EXPECT_LE((apply(A, elbow) - elbow).norm(), 1e-12) << frame;
    const Mat3 R = Eigen::AngleAxisd(frame / 4.0 * 120.0 * std::numbers::pi / 180.0, -Eigen::Vector3d::UnitY()).toRotationMatrix();
    EXPECT_LE((apply(A, wrist) - (elbow + R * (wrist - elbow))).norm(), 1e-12) << frame;
  }
  // A quaternion key (no centre) keeps its own pose when it takes the neighbour's pivot.
  const nlohmann::json q = nlohmann::json::parse(R"({"bones": [
      {"name": "b", "capsule": {"a": [0, 0, 0], "b": [1, 0, 0], "radius": 0.1},
       "keys": [{"frame": 0, "quaternion": [0.7071067811865476, 0, 0, 0.7071067811865476], "translation": [0, 0, 1]},
                {"frame": 2, "rotation": {"axis": [0, 0, 1], "degrees": 0, "center": [5, 0, 0]}}]}]})");
  const Rig rq = parse_rig(q, "rig.json");
  const Eigen::Vector3d X(1, 2, 3);
  EXPECT_LE((apply(rq.bones[0].transform_at(0.0), X) - Eigen::Vector3d(-2, 1, 4)).norm(), 1e-12);
}

TEST(RigKeys, AffineKeysInterpolateComponentWise) {
  Bone bone = capsule_bone("b", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.1);
  bone.motion = BoneMotion::Affine;
  BoneKey k1;
  k1.frame = 4.0;
  k1.affine << 2, 0.5, 0, 1, 0, 1, 0, 0, 0, 0, 0.5, -1;  // shear, stretch, squash
  bone.keys.push_back(k1);
  const Affine34 q = bone.transform_at(1.0);
  EXPECT_LE((q - (0.75 * Affine34::Identity() + 0.25 * k1.affine)).norm(), 1e-14);
}

TEST(RigBinding, VertexInsideTwoBonesFollowsTheFirst) {
  Rig rig;
  rig.bones.push_back(capsule_bone("first", Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), 0.3));
  rig.bones.push_back(capsule_bone("second", Eigen::Vector3d(0.5, -1, 0), Eigen::Vector3d(0.5, 1, 0), 0.3));
  BoneKey moved;
  moved.frame = 1.0;
  moved.translation = Eigen::Vector3d(0, 0, 1);
  rig.bones[1].keys.push_back(moved);
  Eigen::MatrixX3d rest(3, 3);
  rest << 0.5, 0, 0,   // in both: goes to "first"
      0.5, 0.8, 0,     // in "second" only
      3, 3, 3;         // free
  const RigBinding b = bind_rig(rig, rest);
  EXPECT_EQ(b.bone, (std::vector<int>{0, 1, -1}));
  EXPECT_EQ(b.bound_vertices, (std::vector<int>{0, 1}));
  Eigen::VectorXd x = Eigen::VectorXd::Zero(9);
  std::vector<char> fixed(9, 0);
  apply_rig(rig, b, rest, 1.0, x, fixed);
  EXPECT_LE((x.segment<3>(0) - Eigen::Vector3d(0.5, 0, 0)).norm(), 1e-14);
  EXPECT_LE((x.segment<3>(3) - Eigen::Vector3d(0.5, 0.8, 1)).norm(), 1e-14);
  EXPECT_EQ(std::count(fixed.begin(), fixed.end(), 1), 6);
  EXPECT_EQ(fixed[6] + fixed[7] + fixed[8], 0);
}

TEST(RigSprings, GradientAndHessianMatchFiniteDifferences) {
  auto rig = std::make_shared<Rig>();
  rig->bones.push_back(capsule_bone("b", Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), 0.6));
  BoneKey k;
  k.frame = 2.0;
  k.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  k.translation = Eigen::Vector3d(0.1, -0.2, 0.3);
  rig->bones[0].keys.push_back(k);
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 1, 1), Eigen::Vector3i(2, 2, 2));
  BoneSpringForm form(rig, bind_rig(*rig, mesh.vertices), mesh.vertices, 37.0);
  form.set_frame(1.3);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  Eigen::VectorXd x = mesh.rest_positions();
  for (Eigen::Index i = 0; i < x.size(); ++i) x(i) += u(rng);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  form.add_gradient(x, g);
  std::vector<std::vector<int>> cliques;
  form.couplings(cliques);
  BlockHessian H(mesh.num_vertices(), cliques);
  form.add_hessian(x, H);
  const Eigen::MatrixXd K(H.matrix());
  ASSERT_GT(g.norm(), 1.0);
  testing_support::expect_derivatives_match_per_entry(form, x, g, K);
}

nlohmann::json valid_rig_json() {
  return nlohmann::json::parse(R"({
    "binding": "hard",
    "bones": [
      {"name": "upper", "capsule": {"a": [0, 0, 0], "b": [1, 0, 0], "radius": 0.2},
       "keys": [{"frame": 0}]},
      {"name": "lower", "capsule": {"a": [1, 0, 0], "b": [2, 0, 0], "radius": 0.2},
       "keys": [{"frame": 0},
                {"frame": 10, "rotation": {"axis": [0, 0, 1], "degrees": 90, "center": [1, 0, 0]}}]},
      {"name": "skin", "capsule": {"a": [0, 1, 0], "b": [0, 2, 0], "radius": 0.1}, "motion": "affine",
       "keys": [{"frame": 0, "matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]},
                {"frame": 4, "matrix": [[1.2, 0.1, 0, 0], [0, 0.9, 0, 0], [0, 0, 1, 0.5]]}]}
    ]})");
}

TEST(RigReader, ReadsCapsulesRigidAndAffineKeys) {
  const Rig rig = parse_rig(valid_rig_json(), "rig.json");
  ASSERT_EQ(rig.bones.size(), 3u);
  // Rotation about the pivot (1, 0, 0): the bone's far end (2, 0, 0) goes to (1, 1, 0).
  EXPECT_LE((apply(rig.bones[1].transform_at(10.0), Eigen::Vector3d(2, 0, 0)) - Eigen::Vector3d(1, 1, 0)).norm(), 1e-12);
  EXPECT_EQ(rig.bones[2].motion, BoneMotion::Affine);
  EXPECT_NEAR(rig.bones[2].transform_at(2.0)(0, 0), 1.1, 1e-14);
}

TEST(RigReader, RejectsBadFieldsWithFileAndPath) {
  auto expect_error = [](nlohmann::json j, const std::string& needle) {
    const std::string what = error_of([&] { parse_rig(j, "rig.json"); });
    EXPECT_NE(what.find("rig.json"), std::string::npos) << what;
    EXPECT_NE(what.find(needle), std::string::npos) << what;
  };
  nlohmann::json j = valid_rig_json();
  j["bones"][0]["colour"] = "red";
  expect_error(j, "/bones/0");
  j = valid_rig_json();
  j["bones"][1]["keys"][1]["frame"] = 0;
  expect_error(j, "/bones/1/keys/1/frame");
  j = valid_rig_json();
  j["bones"][0]["capsule"]["radius"] = -1;
  expect_error(j, "/bones/0/capsule/radius");
  j = valid_rig_json();
  j["bones"][2]["keys"][0]["matrix"] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  expect_error(j, "/bones/2/keys/0/matrix");
  j = valid_rig_json();
  j["bones"][1]["keys"][0]["quaternion"] = {0, 0, 0, 0};
  expect_error(j, "/bones/1/keys/0/quaternion");
  j = valid_rig_json();
  j["bones"][1]["name"] = "upper";
  expect_error(j, "duplicate bone name");
  j = valid_rig_json();
  j["bones"][0]["mesh"] = "bone.obj";
  expect_error(j, "/bones/0/mesh");
  j = valid_rig_json();
  j["binding"] = "springs";
  expect_error(j, "spring_stiffness");
  EXPECT_NE(error_of([] { load_rig("/nonexistent/rig.json"); }).find("/nonexistent/rig.json"), std::string::npos);
}

TEST(RigReader, ExampleElbowRigMatchesTheExperimentRig) {
  const Rig file = load_rig(std::filesystem::path(SINEW_EXAMPLES) / "rigs" / "elbow_rig.json");
  const Rig code = elbow_rig(12, 120.0);
  ASSERT_EQ(file.bones.size(), code.bones.size());
  for (size_t b = 0; b < code.bones.size(); ++b) {
    EXPECT_EQ(file.bones[b].name, code.bones[b].name);
    for (double frame : {0.0, 3.5, 6.0, 12.0})
      EXPECT_LE((file.bones[b].transform_at(frame) - code.bones[b].transform_at(frame)).norm(), 1e-9) << frame;
  }
}

// Production rigs: intersecting bones with non-rigid (affine) keys. The solve must run, keep
// every value finite and bind each vertex once.
TEST(RigSolve, NoisyIntersectingBonesDriveABlockWithoutFailure) {
  auto disc = std::make_shared<Discretization>(
      box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0.4, 0.4), Eigen::Vector3i(10, 4, 4)));
  MaterialSpec m;
  m.family = "stable_neo_hookean";
  m.target = YoungPoisson{1e4, 0.45};
  Problem problem(disc->mesh().num_vertices());
  problem.add_form(std::make_shared<ElasticForm>(disc, build_material(m)));
  Rig rig;
  rig.bones.push_back(capsule_bone("a", Eigen::Vector3d(0, 0.2, 0.2), Eigen::Vector3d(0.55, 0.2, 0.2), 0.12));
  rig.bones.push_back(capsule_bone("b", Eigen::Vector3d(0.45, 0.2, 0.2), Eigen::Vector3d(1, 0.2, 0.2), 0.12));
  rig.bones[1].motion = BoneMotion::Affine;
  rig.bones[1].keys[0].affine = Affine34::Identity();
  BoneKey k;
  k.frame = 3.0;
  k.affine << 0.9, 0.2, 0, 0.05, -0.3, 1.1, 0.1, 0.1, 0, 0.05, 0.8, 0.05;  // shear + scale, overlaps "a"
  rig.bones[1].keys.push_back(k);
  validate_rig(rig, "test");
  const RigBinding binding = bind_rig(rig, disc->mesh().vertices);
  ASSERT_GT(binding.count_per_bone[0], 0);
  ASSERT_GT(binding.count_per_bone[1], 0);
  auto linear = make_linear_solver(LinearSolverSettings{});
  Eigen::VectorXd x = disc->mesh().rest_positions();
  NewtonSettings s;
  s.test = ConvergenceTest::Absolute;
  s.absolute_tolerance = 1e-6;
  for (int frame = 1; frame <= 3; ++frame) {
    std::vector<char> fixed(x.size(), 0);
    apply_rig(rig, binding, disc->mesh().vertices, frame, x, fixed);
    problem.set_fixed(fixed);
    const NewtonReport r = newton_solve(problem, x, *linear, s);
    EXPECT_TRUE(r.converged) << r.failure;
    EXPECT_TRUE(x.allFinite());
  }
}

}  // namespace
}  // namespace sinew

namespace sinew {
namespace {

// The scene's "rig" and "self_contact" sections: parsed strictly, bound to the mesh, and driven
// by run_scene.
TEST(RigScene, InlineRigDrivesARunAndBadSectionsNameThePath) {
  const auto dir = std::filesystem::temp_directory_path() / "sinew_rig_scene_test";
  std::filesystem::create_directories(dir);
  nlohmann::json scene = nlohmann::json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.2, 0.2]}, "cells": [10, 2, 2]},
    "material": {"family": "stable_neo_hookean", "E": 1e4, "nu": 0.4},
    "rig": {"bones": [
      {"name": "left", "capsule": {"a": [0, 0.1, 0.1], "b": [0.2, 0.1, 0.1], "radius": 0.15}, "keys": [{"frame": 0}]},
      {"name": "right", "capsule": {"a": [0.8, 0.1, 0.1], "b": [1, 0.1, 0.1], "radius": 0.15},
       "keys": [{"frame": 0}, {"frame": 2, "translation": [0.2, 0, 0]}]}]},
    "self_contact": {"stiffness": 1e6},
    "frames": 2
  })");
  const auto file = dir / "scene.json";
  std::ofstream(file) << scene.dump();
  const Scene s = load_scene(file);
  ASSERT_TRUE(s.rig);
  ASSERT_TRUE(s.self_contact);
  const RunSummary r = run_scene(s, RunOptions{});
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_TRUE(r.all_converged());
  // The right end moved with its bone: the bar is 1.2 long.
  EXPECT_NEAR(r.x.reshaped(3, r.x.size() / 3).row(0).maxCoeff(), 1.2, 1e-12);

  auto expect_error = [&](nlohmann::json j, const std::string& needle) {
    std::ofstream(file) << j.dump();
    const std::string what = error_of([&] { load_scene(file); });
    EXPECT_NE(what.find(needle), std::string::npos) << what;
  };
  nlohmann::json bad = scene;
  bad["rig"]["bones"][1]["keys"][1]["translation"] = "far";
  expect_error(bad, "/rig/bones/1/keys/1/translation");
  bad = scene;
  bad["self_contact"]["stiffness"] = -1;
  expect_error(bad, "/self_contact/stiffness");
  bad = scene;
  bad["self_contact"]["samples"] = "faces";
  expect_error(bad, "/self_contact/samples");
  bad = scene;
  bad["rig"] = "missing_rig.json";
  expect_error(bad, "missing_rig.json");
}

// Bones in a dynamic scene: the time stepper moves bound vertices with their bones at each
// step's end (hard), or pulls them there with springs; self-contact stays on in both.
TEST(RigScene, BonesDriveDynamicScenesHardAndWithSprings) {
  const auto dir = std::filesystem::temp_directory_path() / "sinew_rig_dynamic_scene_test";
  std::filesystem::create_directories(dir);
  nlohmann::json scene = nlohmann::json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.2, 0.2]}, "cells": [10, 2, 2]},
    "material": {"family": "stable_neo_hookean", "E": 1e4, "nu": 0.4},
    "density": 100,
    "dynamics": {"time_step": 0.02, "substeps": 2},
    "rig": {"bones": [
      {"name": "left", "capsule": {"a": [0, 0.1, 0.1], "b": [0.2, 0.1, 0.1], "radius": 0.15}, "keys": [{"frame": 0}]},
      {"name": "right", "capsule": {"a": [0.8, 0.1, 0.1], "b": [1, 0.1, 0.1], "radius": 0.15},
       "keys": [{"frame": 0}, {"frame": 3, "translation": [0.3, 0, 0]}]}]},
    "self_contact": {"stiffness": 1e6},
    "frames": 3
  })");
  const auto file = dir / "scene.json";
  auto run = [&](const nlohmann::json& j) {
    std::ofstream(file) << j.dump();
    const Scene s = load_scene(file);
    EXPECT_TRUE(s.dynamics.has_value());
    return run_scene(s, RunOptions{});
  };
  const RunSummary hard = run(scene);
  ASSERT_EQ(hard.frames.size(), 3u);
  EXPECT_TRUE(hard.all_converged());
  const auto hx = hard.x.reshaped(3, hard.x.size() / 3);
  // The right bone's vertices moved by exactly its translation, the left bone's did not move.
  EXPECT_NEAR(hx.row(0).maxCoeff(), 1.3, 1e-12);
  EXPECT_NEAR(hx.row(0).minCoeff(), 0.0, 1e-12);
  // The free middle stretched, lagging the bone (inertia): it moved, but by less than 0.3.
  const VolumeMesh bar = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0.2, 0.2), Eigen::Vector3i(10, 2, 2));
  for (Eigen::Index v = 0; v < bar.num_vertices(); ++v)
    if (std::abs(bar.vertices(v, 0) - 0.5) < 1e-9) {
      EXPECT_GT(hx(0, v) - 0.5, 0.01) << v;
      EXPECT_LT(hx(0, v) - 0.5, 0.3) << v;
    }

  nlohmann::json soft = scene;
  soft["rig"]["binding"] = "springs";
  soft["rig"]["spring_stiffness"] = 1e5;
  const RunSummary springs = run(soft);
  EXPECT_TRUE(springs.all_converged());
  const auto sx = springs.x.reshaped(3, springs.x.size() / 3);
  // Stiff springs: the right end within a millimetre of its bone, not exactly on it.
  EXPECT_NEAR(sx.row(0).maxCoeff(), 1.3, 1e-3);
  EXPECT_GT(std::abs(sx.row(0).maxCoeff() - 1.3), 1e-12);
}

}  // namespace
}  // namespace sinew
