#include "sinew/integrator/implicit_dynamics_integrator.hpp"

#include <fmt/format.h>

namespace sinew {

ImplicitDynamicsIntegrator::ImplicitDynamicsIntegrator(std::shared_ptr<Problem> problem,
                                                       std::unique_ptr<TimeStepper> stepper,
                                                       std::unique_ptr<LinearSolver> linear, DynamicsScheme scheme,
                                                       int substeps)
    : problem_(std::move(problem)),
      stepper_(std::move(stepper)),
      linear_(std::move(linear)),
      scheme_(scheme),
      substeps_(substeps) {}

std::string ImplicitDynamicsIntegrator::description() const {
  return scheme_ == DynamicsScheme::BackwardEuler ? "backward Euler dynamics" : "semi-implicit dynamics";
}

std::string ImplicitDynamicsIntegrator::convergence_test() const {
  if (scheme_ == DynamicsScheme::SemiImplicit)
    return "semi-implicit: one linearised solve per time step, not iterated to equilibrium; a step counts as "
           "converged when its state is valid (finite, no inverted element); the residual after it is reported, "
           "not tested";
  return "backward Euler, every time step: " + describe_convergence_test(stepper_->settings().newton);
}

StepStats ImplicitDynamicsIntegrator::advance_frame(State& state, int frame, const IterationProgress& progress) {
  StepStats stats;
  auto newton_progress = [&](const NewtonIterate& it) {
    if (progress) progress(it.iteration, it.residual);
  };
  const int n = substeps_;
  for (int s = 1; s <= n; ++s) {
    const double frame0 = frame - 1 + double(s - 1) / n, frame1 = frame - 1 + double(s) / n;
    const StepStats r = stepper_->step(state.x, state.v, frame0, frame1, *linear_, newton_progress);
    stats.accumulate(r);
    if (!r.converged) {
      stats.failure = fmt::format("time step {} of {} ({}): {}", s, n, to_string(scheme_), r.failure);
      break;
    }
  }
  return stats;
}

}  // namespace sinew
