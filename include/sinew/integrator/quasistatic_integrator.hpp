#pragma once
// Quasistatic load stepping (paper 000 §6): each frame is a projected-Newton solve of the total
// energy with the prescribed vertices at the frame's positions, started from the previous frame.
// When Newton fails on the frame's whole motion, the motion is halved from the last solved
// state, down to 1/2^kMaxMotionSplits of the frame, and lengthened again after each success -
// unless its tolerance is below round-off (NewtonReport::tolerance_unreachable), where splitting
// cannot help.
#include <memory>

#include "sinew/assembly/problem.hpp"
#include "sinew/forms/penalty_contact_form.hpp"
#include "sinew/integrator/integrator.hpp"
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
                        NewtonSettings newton);

  std::string name() const override { return "quasistatic"; }
  std::string description() const override { return "quasistatic load stepping"; }
  bool dynamic() const override { return false; }
  std::string convergence_test() const override { return describe_convergence_test(newton_); }
  StepStats advance_frame(State& state, int frame, const IterationProgress& progress) override;

 private:
  std::shared_ptr<Problem> problem_;
  PrescribedMotion motion_;
  std::shared_ptr<PenaltyContactForm> contact_;
  std::unique_ptr<LinearSolver> linear_;
  NewtonSettings newton_;
};

}  // namespace sinew
