// Follower pressure (forms/pressure_form.hpp): the force is -p times the current area normal,
// the energy's derivatives where the load is conservative (closed surfaces: EveryForm in
// derivative_check_test.cpp; open surfaces with a held or in-plane rim: here), the energy of an
// open surface as the force's work along each search line, the symmetric stiffness against
// differences of the force, the scale factor; body forces; the scene keys; and a run whose
// reactions balance the follower load.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>

#include "io_test_support.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/forms/external_force_form.hpp"
#include "sinew/forms/pressure_form.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/surface.hpp"
#include "sinew/model/model.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {
namespace {

using nlohmann::json;

VolumeMesh box(ElementKind kind, Eigen::Vector3i cells = Eigen::Vector3i(3, 3, 2)) {
  VolumeMesh m = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1.0, 1.0, 0.5), cells);
  return kind == ElementKind::Hex8 ? m : tetrahedralize_hexes(m);
}

// The boundary faces on the top (z = 0.5) of the box.
std::vector<std::vector<int>> top_faces(const VolumeMesh& m) {
  std::vector<int> top;
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v)
    if (m.vertices(v, 2) > 0.5 - 1e-12) top.push_back(static_cast<int>(v));
  return faces_within(boundary_surface(m), top, m.num_vertices());
}

Eigen::VectorXd perturbed(const Eigen::VectorXd& x, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  Eigen::VectorXd y = x;
  for (Eigen::Index i = 0; i < y.size(); ++i) y(i) += u(rng);
  return y;
}

// The integral of n da over a face, from its corners alone: a triangle's (x1 - x0) x (x2 - x0) / 2,
// a bilinear quad's half cross product of its diagonals.
Vec3 area_normal(const std::vector<int>& f, const Eigen::VectorXd& x) {
  auto p = [&](int k) -> Vec3 { return x.segment<3>(3 * f[k]); };
  return f.size() == 3 ? Vec3(0.5 * (p(1) - p(0)).cross(p(2) - p(0))) : Vec3(0.5 * (p(2) - p(0)).cross(p(3) - p(1)));
}

Eigen::MatrixXd dense_hessian(const Form& form, const Eigen::VectorXd& x) {
  std::vector<std::vector<int>> cliques;
  form.couplings(cliques);
  BlockHessian H(x.size() / 3, cliques);
  form.add_hessian(x, H);
  return Eigen::MatrixXd(H.matrix());
}

Eigen::VectorXd gradient(const Form& form, const Eigen::VectorXd& x) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  form.add_gradient(x, g);
  return g;
}

// Central differences over the DOFs `free`: the largest relative mismatch of the gradient
// against differences of the value, and of the Hessian's free-free block against differences
// of the gradient.
struct Mismatch {
  double gradient = 0.0, hessian = 0.0;
};
Mismatch free_dof_mismatch(const Form& form, const Eigen::VectorXd& x, const std::vector<int>& free) {
  const double h = 1e-6;
  const Eigen::VectorXd g = gradient(form, x);
  const Eigen::MatrixXd H = dense_hessian(form, x);
  Eigen::VectorXd g_free(free.size()), g_fd(free.size());
  Eigen::MatrixXd H_free(free.size(), free.size()), H_fd(free.size(), free.size());
  for (size_t j = 0; j < free.size(); ++j) {
    Eigen::VectorXd xp = x, xm = x;
    xp(free[j]) += h;
    xm(free[j]) -= h;
    g_free(j) = g(free[j]);
    g_fd(j) = (form.value(xp) - form.value(xm)) / (2 * h);
    const Eigen::VectorXd dg = (gradient(form, xp) - gradient(form, xm)) / (2 * h);
    for (size_t i = 0; i < free.size(); ++i) {
      H_fd(i, j) = dg(free[i]);
      H_free(i, j) = H(free[i], free[j]);
    }
  }
  return {(g_free - g_fd).norm() / g_free.norm(), (H_free - H_fd).norm() / H_free.norm()};
}

class Pressure : public ::testing::TestWithParam<ElementKind> {};

TEST_P(Pressure, ForceIsMinusPressureTimesTheCurrentAreaNormal) {
  const VolumeMesh m = box(GetParam());
  const auto faces = top_faces(m);
  ASSERT_EQ(faces.size(), GetParam() == ElementKind::Hex8 ? 9u : 18u);
  const double p = 3.5;
  PressureForm form(faces, m.rest_positions(), p);
  const Eigen::VectorXd x = perturbed(m.rest_positions(), 0.05, 1);
  const Eigen::VectorXd f = form.forces(x);
  // Face by face: the face's nodal forces add up to -p * its area normal.
  Vec3 total = Vec3::Zero();
  for (const auto& face : faces) {
    PressureForm one({face}, m.rest_positions(), p);
    const Eigen::VectorXd fo = one.forces(x);
    Vec3 sum = Vec3::Zero();
    for (int v : face) sum += fo.segment<3>(3 * v);
    EXPECT_LE((sum + p * area_normal(face, x)).norm(), 1e-14);
    total += sum;
  }
  EXPECT_LE((f.reshaped(3, f.size() / 3).rowwise().sum() - total).norm(), 1e-13);
  // At rest the top's normal is +z: the pressure pushes down with p times the area.
  const Eigen::VectorXd f0 = form.forces(m.rest_positions());
  EXPECT_LE((f0.reshaped(3, f0.size() / 3).rowwise().sum() - Vec3(0, 0, -p * 1.0)).norm(), 1e-13);
}

TEST_P(Pressure, FollowsTheRotatedSurface) {
  // A rigid rotation turns the force with the face; the energy does not change.
  const VolumeMesh m = box(GetParam());
  PressureForm form(top_faces(m), m.rest_positions(), 2.0);
  const Mat3 R = Eigen::AngleAxisd(0.9, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
  Eigen::VectorXd x = m.rest_positions(), rotated = x;
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v) rotated.segment<3>(3 * v) = R * x.segment<3>(3 * v);
  const Eigen::VectorXd f0 = form.forces(x), f1 = form.forces(rotated);
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v)
    EXPECT_LE((f1.segment<3>(3 * v) - R * f0.segment<3>(3 * v)).norm(), 1e-14);
  // Closed surface: the energy is p times the change of the enclosed volume, which a rotation keeps.
  PressureForm closed(boundary_surface(m).faces, m.rest_positions(), 2.0);
  EXPECT_NEAR(closed.value(rotated), 0.0, 1e-13);
}

TEST_P(Pressure, ClosedSurfaceEnergyIsPressureTimesVolumeChange) {
  const VolumeMesh m = box(GetParam());
  const Discretization d(m);
  PressureForm form(boundary_surface(m).faces, m.rest_positions(), 4.0);
  EXPECT_TRUE(form.boundary_edges().empty());
  EXPECT_TRUE(form.exact_derivatives());
  const Eigen::VectorXd x = perturbed(m.rest_positions(), 0.05, 2);
  double V = 0.0, V0 = 0.0;  // deformed volume from the elements' J (an independent route)
  for (Eigen::Index e = 0; e < d.num_elements(); ++e)
    for (int q = 0; q < d.quadrature_points(); ++q) {
      V += d.weight(e, q) * d.deformation_gradient(e, q, x).determinant();
      V0 += d.weight(e, q);
    }
  EXPECT_NEAR(form.value(x), 4.0 * (V - V0), 1e-12);
  // No net force on a closed surface.
  const Eigen::VectorXd f = form.forces(x);
  EXPECT_LE(f.reshaped(3, f.size() / 3).rowwise().sum().norm(), 1e-13);
}

// Sets the form's work path to start at `start` (as Newton does at each iterate).
void start_path_at(PressureForm& form, const Eigen::VectorXd& start) { form.linearize_at(start); }

TEST_P(Pressure, OpenSurfaceWithFixedEdgesIsConservativeOnTheFreeDofs) {
  // The top face of the box with its rim held: the interior vertices' DOFs see the energy's
  // gradient and a symmetric stiffness that is its Hessian, wherever the path started (on the
  // held rim).
  const VolumeMesh m = box(GetParam(), Eigen::Vector3i(4, 4, 1));
  PressureForm form(top_faces(m), m.rest_positions(), 5.0);
  EXPECT_FALSE(form.exact_derivatives());
  EXPECT_EQ(form.boundary_edges().size(), 16u);
  std::vector<int> free;
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v) {
    const Vec3 p = m.vertices.row(v).transpose();
    const bool interior = p.z() > 0.5 - 1e-12 && p.x() > 1e-12 && p.x() < 1 - 1e-12 && p.y() > 1e-12 && p.y() < 1 - 1e-12;
    if (!interior) continue;
    for (int i = 0; i < 3; ++i) free.push_back(static_cast<int>(3 * v + i));
  }
  ASSERT_EQ(free.size(), 27u);
  const Eigen::VectorXd x = perturbed(m.rest_positions(), 0.04, 3);  // the rim is held where it is
  Eigen::VectorXd start = x;
  const Eigen::VectorXd other = perturbed(x, 0.05, 7);
  for (int i : free) start(i) = other(i);
  start_path_at(form, start);
  const Mismatch e = free_dof_mismatch(form, x, free);
  EXPECT_LE(e.gradient, 1e-7);
  EXPECT_LE(e.hessian, 1e-7);
}

TEST_P(Pressure, OpenSurfaceWithEdgesInRollerPlanesIsConservativeOnTheFreeDofs) {
  // The top face of the box, its rim vertices free to slide within the side planes x = 0, x = 1,
  // y = 0, y = 1 (rollers, symmetry planes): only the normal DOF of a rim vertex is held.
  const VolumeMesh m = box(GetParam(), Eigen::Vector3i(3, 3, 1));
  PressureForm form(top_faces(m), m.rest_positions(), 5.0);
  Eigen::VectorXd x = perturbed(m.rest_positions(), 0.04, 4);
  std::vector<int> free, all;
  for (Eigen::Index v = 0; v < m.num_vertices(); ++v) {
    const Vec3 p = m.vertices.row(v).transpose();
    for (int i = 0; i < 3; ++i) {
      all.push_back(static_cast<int>(3 * v + i));
      const bool held = i < 2 && (p(i) < 1e-12 || p(i) > 1 - 1e-12);
      if (held) x(3 * v + i) = p(i);  // on its plane
      else free.push_back(static_cast<int>(3 * v + i));
    }
  }
  Eigen::VectorXd start = x;
  const Eigen::VectorXd other = perturbed(x, 0.05, 8);
  for (int i : free) start(i) = other(i);
  start_path_at(form, start);
  const Mismatch e = free_dof_mismatch(form, x, free);
  EXPECT_LE(e.gradient, 1e-7);
  EXPECT_LE(e.hessian, 1e-7);
  // With every DOF free the same load has no potential: differences of the energy away from the
  // path's start do not match the force, and the exact stiffness is not symmetric.
  const Mismatch off = free_dof_mismatch(form, x, all);
  EXPECT_GT(off.gradient, 1e-4);
  EXPECT_GT(off.hessian, 1e-3);
}

TEST_P(Pressure, OpenSurfaceEnergyAlongASearchLineIsTheForcesWork) {
  // From the linearisation point x0 along any direction d, E(x0 + a d) - E(x0) is minus the work
  // of the follower force over the segment (Simpson's rule on a fine grid as the reference), and
  // linearising at x0 leaves E(x0) as it was.
  const VolumeMesh m = box(GetParam(), Eigen::Vector3i(3, 2, 1));
  PressureForm form(top_faces(m), m.rest_positions(), 5.0);
  const Eigen::VectorXd x0 = perturbed(m.rest_positions(), 0.05, 9);
  const Eigen::VectorXd d = perturbed(Eigen::VectorXd::Zero(x0.size()), 0.3, 10);
  const double before = form.value(x0);
  form.linearize_at(x0);
  EXPECT_EQ(form.value(x0), before);
  for (double a : {0.25, 1.0}) {
    const int n = 200;
    double work = 0.0;
    for (int k = 0; k <= n; ++k) {
      const double w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
      work += w * form.forces(x0 + (a * k / n) * d).dot(d);
    }
    work *= a / (3.0 * n);
    EXPECT_NEAR(form.value(x0 + a * d) - before, -work, 1e-10 * std::abs(work)) << "a = " << a;
  }
  // The gradient at the linearisation point is the derivative of the energy there.
  const double h = 1e-6;
  EXPECT_NEAR((form.value(x0 + h * d) - form.value(x0 - h * d)) / (2 * h), gradient(form, x0).dot(d),
              1e-7 * std::abs(gradient(form, x0).dot(d)));
}

TEST_P(Pressure, StiffnessIsTheSymmetricPartOfTheForceDerivative) {
  // Any surface, any state: the Hessian is sym(dg/dx) of the exact follower force.
  const VolumeMesh m = box(GetParam(), Eigen::Vector3i(2, 2, 1));
  PressureForm form(top_faces(m), m.rest_positions(), 3.0);
  const Eigen::VectorXd x = perturbed(m.rest_positions(), 0.05, 5);
  const Eigen::MatrixXd H = dense_hessian(form, x);
  Eigen::MatrixXd K(x.size(), x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    Eigen::VectorXd xp = x, xm = x;
    xp(j) += 1e-6;
    xm(j) -= 1e-6;
    K.col(j) = (gradient(form, xp) - gradient(form, xm)) / 2e-6;
  }
  EXPECT_LE((H - H.transpose()).norm(), 1e-14 * H.norm());
  EXPECT_LE((H - 0.5 * (K + K.transpose())).norm(), 1e-8 * H.norm());
  EXPECT_GT((K - K.transpose()).norm(), 1e-3 * K.norm());  // the exact one is not symmetric here
}

TEST_P(Pressure, ScaleMultipliesEnergyForceAndStiffness) {
  const VolumeMesh m = box(GetParam(), Eigen::Vector3i(2, 2, 1));
  PressureForm form(boundary_surface(m).faces, m.rest_positions(), 3.0);
  const Eigen::VectorXd x = perturbed(m.rest_positions(), 0.05, 6);
  const double E = form.value(x);
  const Eigen::VectorXd g = gradient(form, x);
  const Eigen::MatrixXd H = dense_hessian(form, x);
  form.set_scale(0.25);
  EXPECT_NEAR(form.value(x), 0.25 * E, 1e-15 * std::abs(E) + 1e-300);
  EXPECT_LE((gradient(form, x) - 0.25 * g).norm(), 1e-15 * g.norm());
  EXPECT_LE((dense_hessian(form, x) - 0.25 * H).norm(), 1e-15 * H.norm());
}

INSTANTIATE_TEST_SUITE_P(Faces, Pressure, ::testing::Values(ElementKind::Hex8, ElementKind::Tet4),
                         [](const auto& p) { return std::string(to_string(p.param)); });

TEST(BodyForce, NodalForcesAddUpToForceDensityTimesVolume) {
  for (ElementKind kind : {ElementKind::Hex8, ElementKind::Tet4}) {
    const Discretization d(box(kind));
    const Vec3 b(1.0, -2.0, 30.0);
    const Eigen::VectorXd f = body_forces(d, b);
    EXPECT_LE((f.reshaped(3, f.size() / 3).rowwise().sum() - 0.5 * b).norm(), 1e-13);  // volume 0.5
    // Consistent: a corner node of a lattice gets less than an interior node.
    EXPECT_LT(f(2), f.maxCoeff());
  }
}

json scene_json(const json& loads) {
  json j = json::parse(R"({
    "mesh": {"box": {"min": [0, 0, 0], "max": [1, 0.2, 0.2]}, "cells": [10, 2, 2]},
    "material": {"family": "stable_neo_hookean", "E": 1e6, "nu": 0.3},
    "boundary": [{"name": "wall", "select": {"plane": {"point": [0, 0, 0], "normal": [-1, 0, 0]}}}]})");
  j["loads"] = loads;
  return j;
}

std::string build_error(const json& j) {
  return test::error_message([&] { build_model(parse_scene(j, "dir/scene.json")); });
}

TEST(PressureScene, KeysBuildFormsAndBodyForce) {
  const json loads = json::parse(R"({"pressure": [{"select": {"plane": {"point": [0, 0, 0.2], "normal": [0, 0, 1]}}, "pressure": 200},
                                                 {"select": {"box": {"min": [1, -1, -1], "max": [2, 1, 1]}}, "pressure": -50}],
                                    "body_force": [0, 0, -1000]})");
  const Scene s = parse_scene(scene_json(loads), "dir/scene.json");
  ASSERT_EQ(s.pressures.size(), 2u);
  EXPECT_EQ(s.pressures[1].pressure, -50);
  EXPECT_EQ(s.body_force, Vec3(0, 0, -1000));
  const Model m = build_model(s);
  ASSERT_EQ(m.pressures.size(), 2u);
  EXPECT_EQ(m.pressures[0]->faces().size(), 20u);  // 10 x 2 quads on top
  EXPECT_EQ(m.pressures[1]->faces().size(), 4u);   // the end face
  const Eigen::VectorXd& f = m.external_forces;
  EXPECT_LE((f.reshaped(3, f.size() / 3).rowwise().sum() - Vec3(0, 0, -1000 * 0.04)).norm(), 1e-10);
}

TEST(PressureScene, BadInputIsNamed) {
  test::expect_contains(build_error(scene_json(json::parse(R"({"pressure": [{"select": {"indices": [5]}, "pressure": 1}]})"))),
                        {"dir/scene.json: /loads/pressure/0/select", "selects no boundary face"});
  test::expect_contains(build_error(scene_json(json::parse(R"({"pressure": [{"select": {"indices": [5]}}]})"))),
                        {"/loads/pressure/0", "pressure"});
  test::expect_contains(
      build_error(scene_json(json::parse(R"({"pressure": [{"select": {"indices": [5]}, "pressure": 1, "p": 2}]})"))),
      {"/loads/pressure/0", "p"});
  test::expect_contains(build_error(scene_json(json::parse(R"({"body_force": [0, 1]})"))), {"/loads/body_force"});
}

TEST(PressureScene, CantileverUnderFollowerPressureBalancesItsReaction) {
  // The pressure on the top face stays normal to the bent beam, so the wall's reaction has an
  // axial part (a dead load of the same size would have none), and it balances the follower
  // force computed from the deformed faces' area normals.
  const double p = 2000.0;
  json j = scene_json(json::parse(R"({"pressure": [{"select": {"plane": {"point": [0, 0, 0.2], "normal": [0, 0, 1]}}}]})"));
  j["loads"]["pressure"][0]["pressure"] = p;
  j["frames"] = 2;
  j["solver"] = json::parse(R"({"newton": {"residual_tolerance": 1e-12, "step_tolerance": 1e-9}})");
  const Scene s = parse_scene(j, "dir/scene.json");
  const RunSummary r = run_scene(s, {});
  ASSERT_TRUE(r.all_converged());
  ASSERT_EQ(r.frames.size(), 2u);
  const Model m = build_model(s);
  Vec3 load = Vec3::Zero();
  for (const auto& face : m.pressures[0]->faces()) load -= p * area_normal(face, r.x);
  const Vec3 reaction = r.frames.back().reactions[0];
  EXPECT_LE((reaction + load).norm(), 1e-6 * load.norm()) << reaction.transpose() << " vs " << load.transpose();
  // About p times the top's rest area, downwards: the bent top is tilted and stretched (measured -387 vs -400).
  EXPECT_NEAR(load.z(), -p * 0.2, 0.05 * p * 0.2);
  EXPECT_LT(load.x(), -1e-3 * std::abs(load.z()));   // tilted with the bent surface
}

}  // namespace
}  // namespace sinew
