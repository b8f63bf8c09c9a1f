// Verification against known solutions (docs/verification.md): patch tests on distorted meshes,
// and homogeneous deformations through the whole solver against closed forms derived in the docs
// (equibiaxial stress with rollers through a scene; simple shear with its Poynting stress).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <random>

#include "sinew/assembly/problem.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/material/spec.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/surface.hpp"
#include "sinew/model/model.hpp"
#include "sinew/run/simulation.hpp"
#include "sinew/solver/linear_solver.hpp"
#include "sinew/solver/newton.hpp"

namespace sinew {
namespace {

using nlohmann::json;

BuiltMaterial material(const std::string& family, double E = 1e5, double nu = 0.4) {
  MaterialSpec spec;
  spec.family = family;
  spec.target = YoungPoisson{E, nu};
  return build_material_detailed(spec);
}

// Boundary vertices held at x = F X, interior free; the solution of a homogeneous material is
// then x = F X everywhere (constant stress is divergence free), on any mesh the elements can
// represent affine fields on. Returns the solved positions and the unconstrained gradient.
struct AffineSolve {
  Eigen::VectorXd x, gradient;
  NewtonReport report;
};
AffineSolve solve_affine(const VolumeMesh& mesh, const Material& m, const Mat3& F) {
  auto disc = std::make_shared<Discretization>(mesh, "patch");
  Problem problem(mesh.num_vertices());
  problem.set_discretization(disc);
  auto elastic = std::make_shared<ElasticForm>(disc, std::shared_ptr<const Material>(&m, [](const Material*) {}),
                                               Projection::Clamp);
  problem.add_form(elastic);
  const double size = (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).norm();
  problem.set_scales({size, size * size});
  std::vector<char> fixed(3 * mesh.num_vertices(), 0);
  AffineSolve out;
  out.x = mesh.rest_positions();
  for (int v : boundary_surface(mesh).vertices) {
    out.x.segment<3>(3 * v) = F * mesh.vertices.row(v).transpose();
    fixed[3 * v] = fixed[3 * v + 1] = fixed[3 * v + 2] = 1;
  }
  problem.set_fixed(fixed);
  auto linear = make_linear_solver(LinearSolverSettings{});
  NewtonSettings ns;
  ns.residual_tolerance = 1e-13;
  ns.step_tolerance = 1e-12;
  out.report = newton_solve(problem, out.x, *linear, ns);
  out.gradient = Eigen::VectorXd::Zero(out.x.size());
  elastic->add_gradient(out.x, out.gradient);
  return out;
}

// A 4^3 lattice with every interior vertex moved randomly by up to 0.25 of a cell.
VolumeMesh distorted_lattice(bool tets) {
  VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i(4, 4, 4));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.0625, 0.0625);
  const auto boundary = boundary_surface(mesh).vertices;
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    if (!std::binary_search(boundary.begin(), boundary.end(), static_cast<int>(v)))
      for (int k = 0; k < 3; ++k) mesh.vertices(v, k) += u(rng);
  return tets ? tetrahedralize_hexes(mesh) : mesh;
}

class PatchTest : public ::testing::TestWithParam<std::tuple<bool, std::string>> {};

TEST_P(PatchTest, AffineFieldOnADistortedMeshIsReproducedToRoundOff) {
  const auto [tets, family] = GetParam();
  const VolumeMesh mesh = distorted_lattice(tets);
  Mat3 F;
  F << 1.2, 0.1, -0.05, 0.03, 0.9, 0.15, -0.08, 0.02, 1.1;
  const auto built = material(family);
  const AffineSolve s = solve_affine(mesh, *built.material, F);
  ASSERT_TRUE(s.report.converged) << s.report.failure;
  double worst = 0.0;
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
    worst = std::max(worst, (s.x.segment<3>(3 * v) - F * mesh.vertices.row(v).transpose()).norm());
  EXPECT_LT(worst, 1e-11) << (tets ? "tets" : "hexes") << ", " << family;
  // And the interior is in equilibrium without any Newton iteration at the exact answer.
  EXPECT_GT(s.report.iterations, 0);
}

INSTANTIATE_TEST_SUITE_P(Meshes, PatchTest,
                         ::testing::Combine(::testing::Bool(), ::testing::Values("neo_hookean", "stable_neo_hookean")));

// Simple shear x = X + gamma Y e_x on a unit cube (all boundary vertices prescribed): the force
// on the face y = 1 is P e_y (area 1), with P from the closed forms of docs/verification.md:
//   Neo-Hookean (J = 1): P12 = mu gamma, P22 = 0;
//   Stable Neo-Hookean (Eq. 14, J = 1, I_C = 3 + gamma^2, alpha = 1 + 3 mu / (4 lambda)):
//     P = mu (1 - 1/(I_C + 1)) F + lambda (1 - alpha) F^-T, so P12 = mu gamma (1 - 1/(4 + gamma^2)),
//     P22 = mu (1 - 1/(4 + gamma^2)) - 3 mu / 4 (a Poynting-type normal stress).
TEST(HomogeneousDeformation, SimpleShearFaceForceMatchesTheClosedForms) {
  const double gamma = 0.4;
  Mat3 F = Mat3::Identity();
  F(0, 1) = gamma;
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), Eigen::Vector3i(3, 3, 3));
  for (const std::string family : {"neo_hookean", "stable_neo_hookean"}) {
    const auto built = material(family);
    const double mu = built.parameters.values.at("mu");
    double P12 = mu * gamma, P22 = 0.0;
    if (family == "stable_neo_hookean") {
      P12 = mu * gamma * (1.0 - 1.0 / (4.0 + gamma * gamma));
      P22 = mu * (1.0 - 1.0 / (4.0 + gamma * gamma)) - 0.75 * mu;
    }
    const AffineSolve s = solve_affine(mesh, *built.material, F);
    ASSERT_TRUE(s.report.converged) << s.report.failure;
    // The face's nodal forces: the side faces' contributions at its edges cancel in pairs.
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v)
      if (mesh.vertices(v, 1) > 1.0 - 1e-12) force += s.gradient.segment<3>(3 * v);
    EXPECT_NEAR(force(0), P12, 1e-8 * mu) << family;
    EXPECT_NEAR(force(1), P22, 1e-8 * mu) << family;
    EXPECT_NEAR(force(2), 0.0, 1e-8 * mu) << family;
  }
}

// Equibiaxial stress through a scene: rollers on x = 0, y = 0, z = 0, the faces x = 1 and y = 1
// displaced outwards by the same amount, z free. The thickness stretch t solves P33(l, l, t) = 0;
// for Neo-Hookean (docs/verification.md) mu (t - 1/t) + lambda log(l^2 t) / t = 0, and the face
// force is P11 = mu (l - 1/l) + lambda log(l^2 t) / l per unit rest area.
TEST(HomogeneousDeformation, EquibiaxialStressThroughTheSolver) {
  const double l = 1.25;
  json j = json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 1, 0.5]}, "cells": [3, 3, 2]},
    "material": {"family": "neo_hookean", "E": 1e5, "nu": 0.3},
    "boundary": [
      {"select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}, "components": ["x"]},
      {"select": {"plane": {"point": [0, 0, 0], "normal": [0, -1, 0]}}, "components": ["y"]},
      {"select": {"plane": {"point": [0, 0, 0], "normal": [0, 0, -1]}}, "components": ["z"]},
      {"select": {"plane": {"point": [1, 0, 0], "normal": [1, 0, 0]}}, "components": ["x"],
       "motion": {"type": "displace", "displacement": [0.25, 0, 0]}},
      {"select": {"plane": {"point": [0, 1, 0], "normal": [0, 1, 0]}}, "components": ["y"],
       "motion": {"type": "displace", "displacement": [0, 0.25, 0]}}
    ],
    "solver": {"newton": {"residual_tolerance": 1e-12, "step_tolerance": 1e-10}},
    "frames": 2
  })");
  const Scene scene = parse_scene(j, "equibiaxial.json");
  const RunSummary s = run_scene(scene, RunOptions{});
  ASSERT_EQ(s.frames.size(), 2u);
  ASSERT_TRUE(s.frames[1].converged) << s.frames[1].failure;
  const auto built = build_material_detailed(scene.material);
  const double mu = built.parameters.values.at("mu"), lambda = built.parameters.values.at("lambda");
  auto p33 = [&](double t) { return mu * (t - 1 / t) + lambda * std::log(l * l * t) / t; };
  double lo = 0.3, hi = 1.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (p33(lo) * p33(mid) <= 0 ? hi : lo) = mid;
  }
  const double t = 0.5 * (lo + hi);
  const double P11 = mu * (l - 1 / l) + lambda * std::log(l * l * t) / l;
  const FrameRecord& f = s.frames[1];
  const double area = 1.0 * 0.5;  // rest area of the faces x = 1 and y = 1
  EXPECT_NEAR(f.reactions[3](0), P11 * area, 1e-8 * P11);
  EXPECT_NEAR(f.reactions[4](1), P11 * area, 1e-8 * P11);
  EXPECT_NEAR(f.volume, 0.5 * l * l * t, 1e-9);
  const Eigen::MatrixX3d rest = build_scene_mesh(scene).vertices;
  for (Eigen::Index v = 0; v < rest.rows(); ++v)
    EXPECT_NEAR(s.x(3 * v + 2), t * rest(v, 2), 1e-9) << "vertex " << v;
}

}  // namespace
}  // namespace sinew
