#pragma once
// Quasistatic load stepping (paper 000 §6): each frame is a projected-Newton solve of the total
// energy with the prescribed vertices at the frame's positions, started from the previous frame.
// When Newton fails on the frame's whole motion, the motion is halved from the last solved
// state, down to 1/2^kMaxMotionSplits of the frame, and lengthened again after each success -
// unless its tolerance is below round-off (NewtonReport::tolerance_unreachable), or nothing in
// the problem changes within the step (no prescribed motion, load ramp or moving obstacle), where
// splitting would repeat the same solve.
// Predictor (LoadStepPredictor): each solve starts with the free DOFs moved by the last converged
// increment, scaled to the new step's length (engineering codes' extrapolation), or by the
// solution of the problem linearised at the last solved state with the step's prescribed
// increment applied (the tangent predictor), when that lowers the energy (the energy check is the
// safeguard; Newton's line search does the rest).
// `max_motion_splits` = 0 turns splitting off: a failed solve ends its frame (the paper's one
// solve per frame, as the experiments report it).
#include <memory>

#include "sinew/assembly/problem.hpp"
#include "sinew/forms/penalty_contact_form.hpp"
#include "sinew/integrator/integrator.hpp"
#include "sinew/integrator/load_step_predictor.hpp"
#include "sinew/solver/linear_solver.hpp"
#include "sinew/solver/newton.hpp"

namespace sinew {

inline constexpr int kMaxMotionSplits = 6;

class QuasistaticIntegrator final : public Integrator {
 public:
  // `contact` (may be null) is also one of `problem`'s forms: its obstacles are placed at each
  // solve's target frame.
  QuasistaticIntegrator(std::shared_ptr<Problem> problem, PrescribedMotion motion,
                        std::shared_ptr<PenaltyContactForm> contact, std::unique_ptr<LinearSolver> linear,
                        NewtonSettings newton, LoadStepPredictor predictor = LoadStepPredictor::Auto,
                        int max_motion_splits = kMaxMotionSplits);

  std::string name() const override { return "quasistatic"; }
  std::string description() const override { return "quasistatic load stepping"; }
  bool dynamic() const override { return false; }
  std::string convergence_test() const override { return describe_convergence_test(newton_); }
  StepStats advance_frame(State& state, int frame, const IterationProgress& progress) override;
  // The last increment travels with the checkpoint, so a resumed run predicts as the
  // uninterrupted one did.
  nlohmann::json checkpoint_state() const override;
  void restore_state(const nlohmann::json& state, int frame) override;

 private:
  // Moves the free DOFs of `trial` (prescribed ones already at the target) along the last
  // increment scaled to a step of `length`, if the energy says so; returns whether it did.
  bool extrapolate(Eigen::VectorXd& trial, double length) const;
  // Moves the free DOFs of `trial` by the linearised solution at the solved state `x` (prescribed
  // DOFs of `trial` at the target, loads set for it); returns whether it did. Counts its linear
  // solve in `stats`.
  bool tangent(const Eigen::VectorXd& x, Eigen::VectorXd& trial, StepStats& stats);
  // Whether the problem at the midpoint of (from, to) differs from the one at `to` (prescribed
  // positions, loads or obstacles): if not, a split step is the same solve again.
  bool split_changes_problem(double from, double to, const Eigen::VectorXd& x);

  std::shared_ptr<Problem> problem_;
  PrescribedMotion motion_;
  std::shared_ptr<PenaltyContactForm> contact_;
  std::unique_ptr<LinearSolver> linear_;
  NewtonSettings newton_;
  LoadStepPredictor predictor_ = LoadStepPredictor::Auto;
  int max_motion_splits_ = kMaxMotionSplits;
  Eigen::VectorXd last_increment_;  // x after - x before the last converged solve
  double last_length_ = 0.0;        // its length in frames
};

}  // namespace sinew
