#include "sinew/integrator/quasistatic_integrator.hpp"

#include <fmt/format.h>

namespace sinew {

QuasistaticIntegrator::QuasistaticIntegrator(std::shared_ptr<Problem> problem, PrescribedMotion motion,
                                             std::shared_ptr<PenaltyContactForm> contact,
                                             std::unique_ptr<LinearSolver> linear, NewtonSettings newton)
    : problem_(std::move(problem)),
      motion_(std::move(motion)),
      contact_(std::move(contact)),
      linear_(std::move(linear)),
      newton_(newton) {}

StepStats QuasistaticIntegrator::advance_frame(State& state, int frame, const IterationProgress& progress) {
  StepStats stats;
  auto newton_progress = [&](const NewtonIterate& it) {
    if (progress) progress(it.iteration, it.residual);
  };
  const double min_step = 1.0 / (1 << kMaxMotionSplits);
  double solved = frame - 1.0, step = 1.0;
  Eigen::VectorXd& x = state.x;
  while (solved < frame) {
    const double target = std::min<double>(frame, solved + step);
    Eigen::VectorXd trial = x;
    std::vector<char> fixed(static_cast<size_t>(trial.size()), 0);
    motion_(target, trial, fixed);
    problem_->set_fixed(fixed);
    if (contact_) contact_->begin_step(x, solved, target, 0.0);  // obstacles at `target`
    const NewtonReport r = newton_solve(*problem_, trial, *linear_, newton_, newton_progress);
    stats.newton_iterations += r.iterations;
    stats.linear_iterations += r.linear_iterations;
    stats.assembly_seconds += r.assembly_seconds;
    stats.solve_seconds += r.solve_seconds;
    stats.residual = r.residual;
    stats.force_scale = r.force_scale;
    stats.energy = r.energy;
    if (r.converged) {
      x = trial;
      solved = target;
      stats.substeps += 1;
      step = std::min(1.0, 2.0 * step);
    } else if (step > min_step && !r.tolerance_unreachable) {
      step *= 0.5;
    } else if (step > min_step) {
      // The tolerance, not the size of the motion, is the problem: a smaller step would fail the
      // same way, only slower.
      x = trial;
      stats.converged = false;
      stats.failure = r.failure + " (not split: a smaller motion step cannot reach it either)";
      break;
    } else {
      x = trial;  // kept for inspection, never continued from
      stats.converged = false;
      stats.failure = fmt::format("{} (even with the frame's motion split into steps of 1/{})", r.failure,
                                  1 << kMaxMotionSplits);
      break;
    }
  }
  return stats;
}

}  // namespace sinew
