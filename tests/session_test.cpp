// Session (run/session.hpp): a scene stepped frame by frame gives run_scene's frames; boundary
// motions and external forces changed between frames take effect from the next frame; bad
// changes are sinew::Errors naming the boundary condition. element_stresses against the material.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io_test_support.hpp"
#include "sinew/core/error.hpp"
#include "sinew/run/element_stresses.hpp"
#include "sinew/run/session.hpp"

namespace sinew {
namespace {

using nlohmann::json;

// A 1 x 0.25 x 0.25 bar of 6 x 2 x 2 hexes, left end pinned, right end pulled 0.1 per frame.
Scene bar(const std::string& element = "hex") {
  json j = json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.25, 0.25]}, "cells": [6, 2, 2]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.45},
    "boundary": [
      {"name": "left", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}},
      {"name": "right", "select": {"plane": {"point": [1, 0, 0], "normal": [1, 0, 0]}},
       "motion": {"type": "translate", "per_frame": [0.1, 0, 0]}}
    ],
    "solver": {"newton": {"convergence": "absolute", "tolerance": 1e-8}},
    "frames": 2
  })");
  j["mesh"]["element"] = element;
  return parse_scene(j, "bar.json");
}

TEST(Session, SteppingGivesTheFramesOfARun) {
  const Scene scene = bar();
  const RunSummary run = run_scene(scene, {});
  Session session(scene);
  EXPECT_EQ(session.frame(), 0);
  for (int f = 1; f <= 2; ++f) {
    const FrameRecord& r = session.step();
    EXPECT_EQ(r.frame, f);
    EXPECT_EQ(r.newton_iterations, run.frames[f - 1].newton_iterations);
    EXPECT_NEAR(r.volume, run.frames[f - 1].volume, 1e-12);
  }
  EXPECT_EQ(session.frame(), 2);
  EXPECT_LT((session.state().x - run.x).lpNorm<Eigen::Infinity>(), 1e-9);
  EXPECT_EQ(session.summary().frames.size(), 2u);
}

TEST(Session, MovedBoundaryReachesItsTargetAtTheNextFrame) {
  Session session(bar());
  const std::vector<int>& right = (*session.model().kinematics)[1].vertices;
  const Eigen::MatrixX3d& rest = session.model().disc->mesh().vertices;
  RigidTransform target;
  target.t = Eigen::Vector3d(0.25, 0.0, 0.05);
  session.move_boundary(1, target);
  ASSERT_TRUE(session.step().converged);
  for (int v : right)
    EXPECT_LT((session.state().x.segment<3>(3 * v) - (rest.row(v).transpose() + target.t)).norm(), 1e-12);
  // Held afterwards, whatever the scene's motion was.
  ASSERT_TRUE(session.step().converged);
  EXPECT_LT((session.boundary_transform(1, 2.0).t - target.t).norm(), 1e-15);
  for (int v : right)
    EXPECT_LT((session.state().x.segment<3>(3 * v) - (rest.row(v).transpose() + target.t)).norm(), 1e-12);
  // A new motion replaces it: a function of the frame number, from the rest pose.
  session.set_boundary_motion(1, Translation{Eigen::Vector3d(0.05, 0, 0)});
  ASSERT_TRUE(session.step().converged);
  for (int v : right) EXPECT_NEAR(session.state().x(3 * v) - rest(v, 0), 0.15, 1e-12);
}

TEST(Session, BadChangesNameTheBoundaryCondition) {
  Session session(bar());
  RigidTransform squashed;
  squashed.R = 0.5 * Mat3::Identity();
  test::expect_contains(test::error_message([&] { session.move_boundary(1, squashed); }),
                        {"bar.json: /boundary/1/motion", "rotation matrix"});
  test::expect_contains(test::error_message([&] { session.move_boundary(2, {}); }),
                        {"no boundary condition 2 (the scene has 2)"});
  Rotation zero_axis;
  zero_axis.axis.setZero();
  EXPECT_THROW(session.set_boundary_motion(0, zero_axis), Error);
  test::expect_contains(test::error_message([&] { session.set_external_forces(Eigen::VectorXd::Zero(3)); }),
                        {"external forces", "need"});
}

TEST(Session, ExternalForcesChangedBetweenFramesAreBalancedByTheSupports) {
  Scene scene = bar();
  scene.boundary.pop_back();  // only the left end held
  Session session(scene);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(session.external_forces().size());
  const Eigen::MatrixX3d& rest = session.model().disc->mesh().vertices;
  for (Eigen::Index v = 0; v < rest.rows(); ++v)
    if (rest(v, 0) > 1.0 - 1e-9) f(3 * v + 2) = -1.0;
  session.set_external_forces(f);
  const FrameRecord& r = session.step();
  ASSERT_TRUE(r.converged);
  const Eigen::Vector3d total = f.reshaped(3, f.size() / 3).rowwise().sum();
  EXPECT_LT((r.reactions[0] + total).norm(), 1e-5 * total.norm());
  EXPECT_LT((session.summary().external_force - total).norm(), 1e-12);
  EXPECT_LT((r.external_force - total).norm(), 1e-12);
}

TEST(Session, ExternalForcesReplaceTheScenesRampedLoads) {
  json j = json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.25, 0.25]}, "cells": [6, 2, 2]},
    "material": {"family": "stable_neo_hookean", "E": 1e5, "nu": 0.45},
    "boundary": [{"name": "wall", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}}],
    "loads": {"point": [{"select": {"box": {"min": [1, 0, 0], "max": [1, 0.25, 0.25]}}, "force": [0, 0, -5],
                         "amplitude": "ramp"}]},
    "frames": 4
  })");
  Session session(parse_scene(j, "ramp.json"));
  EXPECT_NEAR(session.step().external_force.z(), -5 * 9 / 4.0, 1e-12);  // 9 tip vertices, 1/4 of the ramp
  Eigen::VectorXd f = Eigen::VectorXd::Zero(session.external_forces().size());
  f(3 * 5 + 1) = 2.0;  // one vertex, sideways
  session.set_external_forces(f);
  const FrameRecord& r = session.step();
  ASSERT_TRUE(r.converged);
  EXPECT_LT((r.external_force - Eigen::Vector3d(0, 2, 0)).norm(), 1e-12);  // the ramp no longer applies
  EXPECT_LT((r.reactions[0] + Eigen::Vector3d(0, 2, 0)).norm(), 1e-4);
  EXPECT_LT((session.external_forces() - f).norm(), 1e-15);
}

TEST(ElementStresses, AreThoseOfTheMaterialOnTetrahedra) {
  Session session(bar("tet"));
  session.step();
  const Model& model = session.model();
  const ElementStresses s = element_stresses(model, session.state().x);
  const Discretization& d = *model.disc;
  ASSERT_EQ(s.pk1.rows(), d.num_elements());
  for (Eigen::Index e = 0; e < d.num_elements(); e += 7) {
    const Mat3 F = d.deformation_gradient(e, 0, session.state().x);  // one point: linear tetrahedra
    const Mat3 P = model.material.material->pk1(F);
    const Mat3 sigma = P * F.transpose() / F.determinant();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        EXPECT_NEAR(s.pk1(e, 3 * i + j), P(i, j), 1e-9 * P.norm());
        EXPECT_NEAR(s.cauchy(e, 3 * i + j), sigma(i, j), 1e-9 * sigma.norm());
      }
  }
  const ElementStresses rest = element_stresses(model, model.initial.x);
  EXPECT_LT(rest.pk1.cwiseAbs().maxCoeff(), 1e-9);
}

}  // namespace
}  // namespace sinew
