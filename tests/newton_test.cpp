// The quasistatic Newton solver on small versions of paper 000's twist test.
#include <gtest/gtest.h>

#include <numbers>

#include "sinew/forms/elastic_form.hpp"
#include "sinew/motion/prescribed_motion.hpp"
#include "sinew/material/families/corotational.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/selection.hpp"
#include "sinew/solver/newton.hpp"

namespace sinew {
namespace {

// Co-rotational elasticity resolves the first quarter twist; its second one collapses
// (paper 000 §6, 223 Newton iterations), so these solver tests stop after one.
struct TwistOutcome {
  NewtonReport first;
  double min_J = 0.0;
};

TwistOutcome run_twist(const std::string& solver_kind) {
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1), Eigen::Vector3i(5, 5, 5));
  auto disc = std::make_shared<Discretization>(mesh);
  auto form = std::make_shared<ElasticForm>(disc, std::make_shared<LinearCorotational>(20.0, 1.0));
  Problem problem(mesh.num_vertices());
  problem.add_form(form);
  std::vector<KinematicCondition> bcs;
  bcs.push_back({select_vertices(mesh.vertices, PlaneSelector{{0, 0, 0}, {0, 0, -1}}, "bottom"), Pinned{}, "bottom", {true, true, true}, {}});
  bcs.push_back({select_vertices(mesh.vertices, PlaneSelector{{0, 0, 1}, {0, 0, 1}}, "top"),
                 Rotation{{0.5, 0.5, 1.0}, {0, 0, 1}, std::numbers::pi / 2}, "top", {true, true, true}, {}});
  LinearSolverSettings ls;
  ls.kind = solver_kind;
  auto linear = make_linear_solver(ls);
  NewtonSettings settings;
  settings.test = ConvergenceTest::Absolute;
  settings.absolute_tolerance = 1e-8;
  settings.linear_tolerance = 1e-6;
  Eigen::VectorXd x = mesh.rest_positions();
  TwistOutcome out;
  std::vector<char> fixed(x.size(), 0);
  apply_kinematics(bcs, mesh.vertices, 1.0, x, fixed);
  problem.set_fixed(fixed);
  out.first = newton_solve(problem, x, *linear, settings);
  out.min_J = form->element_fields(x).J.minCoeff();
  return out;
}

TEST(Newton, ResolvesAQuarterTwistWithCholmod) {
  const TwistOutcome r = run_twist("cholmod");
  EXPECT_TRUE(r.first.converged) << r.first.failure;
  EXPECT_LE(r.first.residual, 1e-8);
  EXPECT_GT(r.min_J, 0.0);
  std::printf("twist 5^3 corotational (cholmod): Newton %d, min J %.3f\n", r.first.iterations, r.min_J);
}

TEST(Newton, PcgGivesTheSameTwistAsCholmod) {
  const TwistOutcome a = run_twist("cholmod");
  const TwistOutcome b = run_twist("pcg");
  EXPECT_TRUE(b.first.converged) << b.first.failure;
  EXPECT_GT(b.first.linear_iterations, b.first.iterations);  // CG counts its own iterations
  EXPECT_NEAR(a.first.energy, b.first.energy, 1e-8 * std::abs(a.first.energy));
}

}  // namespace
}  // namespace sinew
