#include "sinew/integrator/time_stepper.hpp"

#include <fmt/format.h>

namespace sinew {

const char* to_string(DynamicsScheme scheme) {
  return scheme == DynamicsScheme::BackwardEuler ? "backward_euler" : "semi_implicit";
}

TimeStepper::TimeStepper(Problem& problem, std::shared_ptr<InertiaForm> inertia, std::shared_ptr<DampingForm> damping,
                         std::shared_ptr<PenaltyContactForm> contact, std::vector<KinematicCondition> kinematics,
                         Eigen::MatrixX3d rest, TimeStepSettings settings)
    : problem_(problem), inertia_(std::move(inertia)), damping_(std::move(damping)), contact_(std::move(contact)),
      kinematics_(std::move(kinematics)), rest_(std::move(rest)), settings_(settings) {}

StepStats TimeStepper::step(Eigen::VectorXd& x, Eigen::VectorXd& v, double frame0, double frame1,
                             LinearSolver& linear, const std::function<void(const NewtonIterate&)>& progress) {
  const double h = time_step();
  inertia_->set_prediction(x, v);
  if (damping_) damping_->begin_step(x);
  if (contact_) contact_->begin_step(x, frame0, frame1, settings_.friction_velocity * h);

  // Start from x_n (always inside the energy's domain) with the constrained vertices moved to
  // their end-of-step positions.
  Eigen::VectorXd trial = x;
  std::vector<char> fixed(trial.size(), 0);
  apply_kinematics(kinematics_, rest_, frame1, trial, fixed);
  for (const auto& hook : hooks_) hook(frame1, rest_, trial, fixed);
  problem_.set_fixed(fixed);

  NewtonSettings newton = settings_.newton;
  const bool one_step = settings_.integrator == DynamicsScheme::SemiImplicit;
  if (one_step) newton.max_iterations = 1;
  const NewtonReport r = newton_solve(problem_, trial, linear, newton, progress);

  StepStats out;
  out.substeps = 1;
  out.newton_iterations = r.iterations;
  out.linear_iterations = r.linear_iterations;
  out.residual = r.residual;
  out.force_scale = r.force_scale;
  out.energy = r.energy;
  out.assembly_seconds = r.assembly_seconds;
  out.solve_seconds = r.solve_seconds;
  // One linearised solve per step is the semi-implicit method: its "convergence" is a valid
  // state after the step (Newton reports the iteration cap, which is expected here).
  out.converged = r.converged || (one_step && r.iterations == 1 && problem_.is_valid(trial));
  if (!out.converged) {
    out.substeps = 0;
    out.failure = r.failure;
    return out;
  }
  v = (trial - x) / h;
  x = trial;
  return out;
}

}  // namespace sinew
