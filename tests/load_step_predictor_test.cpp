// The quasistatic integrator's load-step predictors (integrator/load_step_predictor.hpp): the
// tangent predictor solves the problem linearised at the solved state with the step's prescribed
// increment applied, so the residual it leaves is second order in the step; moving only the
// prescribed vertices leaves a first-order one.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sinew/forms/elastic_form.hpp"
#include "sinew/integrator/quasistatic_integrator.hpp"
#include "sinew/material/families/stable_neo_hookean.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/selection.hpp"
#include "sinew/motion/prescribed_motion.hpp"

namespace sinew {
namespace {

// A 4 x 2 x 2 bar of stable Neo-Hookean hexahedra (nu = 0.45), the x = 0 end pinned and the
// x = 1 end moved by `scale` (stretch and shear) per frame, or turned by `twist` radians per
// frame about the bar's axis. Returns the residual at the start of
// frame `frames` (Newton takes no iteration), after `frames - 1` solved frames.
double residual_after_prediction(LoadStepPredictor predictor, double scale, int frames = 1,
                                 StepStats* last = nullptr, double twist = 0.0) {
  const VolumeMesh mesh = box_lattice(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0.5, 0.5), Eigen::Vector3i(4, 2, 2));
  auto disc = std::make_shared<Discretization>(mesh);
  const double E = 1e5, nu = 0.45, lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  auto problem = std::make_shared<Problem>(mesh.num_vertices());
  problem->add_form(std::make_shared<ElasticForm>(disc, std::make_shared<StableNeoHookean>(lambda, mu)));
  problem->set_discretization(disc);
  std::vector<KinematicCondition> bcs;
  bcs.push_back({select_vertices(mesh.vertices, PlaneSelector{{0, 0, 0}, {-1, 0, 0}}, "left"), Pinned{}, "left",
                 {true, true, true}, {}});
  if (twist != 0.0)
    bcs.push_back({select_vertices(mesh.vertices, PlaneSelector{{1, 0, 0}, {1, 0, 0}}, "right"),
                   Rotation{{1, 0.25, 0.25}, {1, 0, 0}, twist}, "right", {true, true, true}, {}});
  else
    bcs.push_back({select_vertices(mesh.vertices, PlaneSelector{{1, 0, 0}, {1, 0, 0}}, "right"),
                   Translation{Eigen::Vector3d(0.2, 0.1, -0.05) * scale}, "right", {true, true, true}, {}});
  PrescribedMotion motion = [bcs, vertices = mesh.vertices](double frame, Eigen::VectorXd& y, std::vector<char>& fixed) {
    apply_kinematics(bcs, vertices, frame, y, fixed);
  };
  LinearSolverSettings ls;  // CHOLMOD: the linearised problem is solved exactly
  NewtonSettings solved;
  solved.test = ConvergenceTest::Absolute;
  solved.absolute_tolerance = 1e-9;
  solved.exact_tail = true;
  State state{mesh.rest_positions(), {}};
  if (frames > 1) {
    QuasistaticIntegrator integrator(problem, motion, nullptr, make_linear_solver(ls), solved, predictor, 0);
    for (int f = 1; f < frames; ++f) {
      const StepStats s = integrator.advance_frame(state, f, {});
      EXPECT_TRUE(s.converged) << s.failure;
    }
    NewtonSettings none = solved;
    none.max_iterations = 0;  // only the prediction
    QuasistaticIntegrator probe(problem, motion, nullptr, make_linear_solver(ls), none, predictor, 0);
    probe.restore_state(integrator.checkpoint_state(), frames);
    const StepStats s = probe.advance_frame(state, frames, {});
    if (last) *last = s;
    return s.residual;
  }
  NewtonSettings none = solved;
  none.max_iterations = 0;
  QuasistaticIntegrator probe(problem, motion, nullptr, make_linear_solver(ls), none, predictor, 0);
  const StepStats s = probe.advance_frame(state, 1, {});
  if (last) *last = s;
  return s.residual;
}

TEST(LoadStepPredictor, TangentResidualIsSecondOrderInTheStep) {
  // Halving the step quarters the residual the tangent predictor leaves (the linearisation's
  // error), while the plain start (only the prescribed end moved) halves it.
  const double tangent_big = residual_after_prediction(LoadStepPredictor::Tangent, 1e-2);
  const double tangent_small = residual_after_prediction(LoadStepPredictor::Tangent, 1e-3);
  const double plain_big = residual_after_prediction(LoadStepPredictor::None, 1e-2);
  const double plain_small = residual_after_prediction(LoadStepPredictor::None, 1e-3);
  std::printf("residual after prediction, step 1e-2 / 1e-3: tangent %.3e / %.3e, none %.3e / %.3e\n", tangent_big,
              tangent_small, plain_big, plain_small);
  EXPECT_NEAR(plain_big / plain_small, 10.0, 0.5);
  EXPECT_GT(tangent_big / tangent_small, 70.0);
  EXPECT_LT(tangent_big / tangent_small, 130.0);
  EXPECT_LT(tangent_big, 0.05 * plain_big);
}

TEST(LoadStepPredictor, AutoUsesTheTangentFirstAndExtrapolatesAfter) {
  StepStats first, second;
  const double auto_first = residual_after_prediction(LoadStepPredictor::Auto, 0.5, 1, &first);
  const double tangent_first = residual_after_prediction(LoadStepPredictor::Tangent, 0.5, 1);
  EXPECT_EQ(auto_first, tangent_first);
  EXPECT_EQ(first.counter("tangent_predicted_steps"), 1.0);
  EXPECT_GT(first.counter("tangent_predictor_linear_iterations"), 0.0);
  residual_after_prediction(LoadStepPredictor::Auto, 0.5, 2, &second);
  EXPECT_EQ(second.counter("predicted_steps"), 1.0);
  EXPECT_EQ(second.counter("tangent_predicted_steps"), 0.0);
  // A large first step (the end moved by a fifth of the bar): the tangent start is much nearer
  // equilibrium than the plain one.
  EXPECT_LT(auto_first, 0.1 * residual_after_prediction(LoadStepPredictor::None, 0.5));
}

TEST(LoadStepPredictor, TangentIsRejectedWhereTheLinearisationDoesNotHold) {
  // A quarter turn of the end in one step: the linearised interior moves along chords, sheared
  // and compressed; its energy falls far short of the quadratic model's prediction, so the plain
  // start is kept (paper 000's twist needs fewer Newton iterations from it).
  StepStats turned;
  const double tangent = residual_after_prediction(LoadStepPredictor::Tangent, 0.0, 1, &turned, std::numbers::pi / 2);
  const double plain = residual_after_prediction(LoadStepPredictor::None, 0.0, 1, nullptr, std::numbers::pi / 2);
  EXPECT_EQ(turned.counter("tangent_predicted_steps"), 0.0);
  EXPECT_GT(turned.counter("tangent_predictor_linear_iterations"), 0.0);  // it was tried
  EXPECT_EQ(tangent, plain);
  // A small turn is within the linearisation's reach.
  StepStats small;
  residual_after_prediction(LoadStepPredictor::Tangent, 0.0, 1, &small, 0.01);
  EXPECT_EQ(small.counter("tangent_predicted_steps"), 1.0);
}

}  // namespace
}  // namespace sinew
