#include "sinew/integrator/quasistatic_integrator.hpp"

#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

QuasistaticIntegrator::QuasistaticIntegrator(std::shared_ptr<Problem> problem, PrescribedMotion motion,
                                             std::shared_ptr<PenaltyContactForm> contact,
                                             std::unique_ptr<LinearSolver> linear, NewtonSettings newton,
                                             LoadStepPredictor predictor, int max_motion_splits)
    : problem_(std::move(problem)),
      motion_(std::move(motion)),
      contact_(std::move(contact)),
      linear_(std::move(linear)),
      newton_(newton),
      predictor_(predictor),
      max_motion_splits_(max_motion_splits) {
  if (max_motion_splits_ < 0 || max_motion_splits_ > 30)
    throw Error(fmt::format("max_motion_splits must be in [0, 30], not {}", max_motion_splits_), "quasistatic integrator");
}

bool QuasistaticIntegrator::extrapolate(Eigen::VectorXd& trial, double length) const {
  if (last_length_ <= 0.0 || last_increment_.size() != trial.size()) return false;
  // The fixed mask is in the problem's vertex frames (rotated for direction conditions).
  const std::vector<char>& fixed = problem_->fixed();
  Eigen::VectorXd increment = (length / last_length_) * last_increment_;
  problem_->to_local(increment);
  for (Eigen::Index i = 0; i < increment.size(); ++i)
    if (fixed[static_cast<size_t>(i)]) increment(i) = 0.0;
  problem_->to_global(increment);
  const Eigen::VectorXd predicted = trial + increment;
  // The safeguard: only a start with less energy (finite: no inverted element of a log-based
  // material) replaces the plain one.
  const double plain = problem_->value(trial), extrapolated = problem_->value(predicted);
  if (!(std::isfinite(extrapolated) && extrapolated < plain)) return false;
  trial = predicted;
  return true;
}

bool QuasistaticIntegrator::tangent(const Eigen::VectorXd& x, Eigen::VectorXd& trial, StepStats& stats) {
  auto t0 = std::chrono::steady_clock::now();
  // The linearised problem at x: H(x) delta = -(g(x) + H(x) d) on the free DOFs, d = the step's
  // prescribed increment (trial - x). g and H d come from central differences of the gradient
  // along d (the Hessian's fixed rows and columns are replaced by the identity, so it cannot
  // give the coupling of free to prescribed DOFs); the step h moves no DOF by more than 1e-6 of
  // the body's size, far above round-off and far below any nonlinearity.
  const Eigen::VectorXd d = trial - x;
  Eigen::VectorXd rhs;
  const double largest = d.lpNorm<Eigen::Infinity>();
  if (largest > 0.0) {
    double size = problem_->scales().length;
    if (!(size > 0.0)) {
      const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> p(x.data(), 3, x.size() / 3);
      size = (p.rowwise().maxCoeff() - p.rowwise().minCoeff()).norm();
    }
    const double h = std::min(1.0, 1e-6 * size / largest);
    const Eigen::VectorXd plus = x + h * d, minus = x - h * d;
    if (!problem_->is_valid(plus) || !problem_->is_valid(minus)) return false;
    const Eigen::VectorXd g_plus = problem_->gradient(plus), g_minus = problem_->gradient(minus);
    rhs = 0.5 * (g_plus + g_minus) + (0.5 / h) * (g_plus - g_minus);
  } else {
    rhs = problem_->gradient(x);  // only the loads change
  }
  if (!rhs.allFinite() || rhs.squaredNorm() == 0.0) return false;
  const LinearOperator& H = problem_->hessian(x);
  stats.assembly_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t0 = std::chrono::steady_clock::now();
  Eigen::VectorXd delta;
  const LinearSolveReport lin =
      linear_->solve(H, -rhs, delta, newton_.linear_tolerance, SolverContext{problem_->discretization(), problem_->fixed()});
  stats.solve_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  stats.linear_iterations += lin.iterations;
  stats.add_counter("tangent_predictor_linear_iterations", lin.iterations);
  if (!delta.allFinite()) return false;
  const Eigen::VectorXd delta_local = delta;
  problem_->to_global(delta);
  // The safeguard, as a trust region's: the prediction is taken only where the linearisation
  // holds, i.e. the full step lowers the energy by at least a quarter of what the quadratic model
  // predicts, -1/2 rhs.delta (H delta = -rhs). A large rotation of the prescribed vertices (a
  // twist) fails it: its linearised interior is sheared and compressed, and Newton does better
  // from the plain start; a stretch passes it with a ratio near 1.
  t0 = std::chrono::steady_clock::now();
  const double model_decrease = -0.5 * rhs.dot(delta_local);
  const Eigen::VectorXd predicted = trial + delta;
  const double decrease = problem_->value(trial) - problem_->value(predicted);
  const bool moved = model_decrease > 0.0 && std::isfinite(decrease) && decrease >= 0.25 * model_decrease;
  if (moved) trial = predicted;
  stats.assembly_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return moved;
}

bool QuasistaticIntegrator::split_changes_problem(double from, double to, const Eigen::VectorXd& x) {
  if (contact_) return true;  // obstacles may move within the step
  Eigen::VectorXd at_end = x, at_middle = x;
  std::vector<char> fixed_end(static_cast<size_t>(x.size()), 0), fixed_middle = fixed_end;
  motion_(to, at_end, fixed_end);
  problem_->set_fixed(fixed_end);
  // A motion that inverts elements at the end of the step is what splitting is for.
  if (!problem_->is_valid(at_end)) return true;
  const Eigen::VectorXd g_end = problem_->gradient(at_end);
  motion_(0.5 * (from + to), at_middle, fixed_middle);  // also sets the loads of the midpoint
  problem_->set_fixed(fixed_middle);
  const Eigen::VectorXd g_middle = problem_->gradient(at_end);
  return at_end != at_middle || fixed_end != fixed_middle || g_end != g_middle;
}

StepStats QuasistaticIntegrator::advance_frame(State& state, int frame, const IterationProgress& progress) {
  StepStats stats;
  auto newton_progress = [&](const NewtonIterate& it) {
    if (progress) progress(it.iteration, it.residual);
  };
  const double min_step = 1.0 / (1 << max_motion_splits_);
  double solved = frame - 1.0, step = 1.0;
  Eigen::VectorXd& x = state.x;
  while (solved < frame) {
    const double target = std::min<double>(frame, solved + step);
    Eigen::VectorXd trial = x;
    std::vector<char> fixed(static_cast<size_t>(trial.size()), 0);
    motion_(target, trial, fixed);
    problem_->set_fixed(fixed);
    if (contact_) contact_->begin_step(x, solved, target, 0.0);  // obstacles at `target`
    const bool may_extrapolate = predictor_ == LoadStepPredictor::Extrapolate || predictor_ == LoadStepPredictor::Auto;
    bool predicted = may_extrapolate && extrapolate(trial, target - solved);
    if (predicted) stats.add_counter("predicted_steps", 1.0);
    // Auto: the tangent where there is no increment to extrapolate (the first step), or where
    // extrapolating does not lower the energy (the motion turned).
    if (!predicted && (predictor_ == LoadStepPredictor::Tangent || predictor_ == LoadStepPredictor::Auto) &&
        tangent(x, trial, stats))
      stats.add_counter("tangent_predicted_steps", 1.0);
    const NewtonReport r = newton_solve(*problem_, trial, *linear_, newton_, newton_progress, &x);
    stats.newton_iterations += r.iterations;
    stats.linear_iterations += r.linear_iterations;
    stats.assembly_seconds += r.assembly_seconds;
    stats.solve_seconds += r.solve_seconds;
    stats.residual = r.residual;
    stats.force_scale = r.force_scale;
    stats.energy = r.energy;
    if (newton_.exact_tail) {
      stats.add_counter("exact_hessian_iterations", r.exact_iterations);
      stats.add_counter("exact_hessian_fallbacks", r.exact_fallbacks);
      stats.add_counter("exact_hessian_short_steps", r.exact_short_steps);
    }
    if (r.converged) {
      last_increment_ = trial - x;
      last_length_ = target - solved;
      x = trial;
      solved = target;
      stats.substeps += 1;
      step = std::min(1.0, 2.0 * step);
    } else if (step > min_step && !r.tolerance_unreachable && split_changes_problem(solved, target, x)) {
      step *= 0.5;
    } else if (step > min_step) {
      // A smaller step would fail the same way, only slower: the tolerance is below round-off,
      // or nothing changes within the step.
      x = trial;
      stats.converged = false;
      stats.failure = r.failure + (r.tolerance_unreachable
                                       ? " (not split: a smaller motion step cannot reach it either)"
                                       : " (not split: no motion, load or obstacle changes within the step, so a "
                                         "smaller step would repeat the same solve)");
      break;
    } else {
      x = trial;  // kept for inspection, never continued from
      stats.converged = false;
      stats.failure = max_motion_splits_ == 0
                          ? r.failure
                          : fmt::format("{} (even with the frame's motion split into steps of 1/{})", r.failure,
                                        1 << max_motion_splits_);
      break;
    }
  }
  return stats;
}

nlohmann::json QuasistaticIntegrator::checkpoint_state() const {
  if (predictor_ == LoadStepPredictor::None || last_length_ <= 0.0) return nlohmann::json::object();
  return {{"last_increment", std::vector<double>(last_increment_.data(), last_increment_.data() + last_increment_.size())},
          {"last_length", last_length_}};
}

void QuasistaticIntegrator::restore_state(const nlohmann::json& state, int /*frame*/) {
  last_increment_.resize(0);
  last_length_ = 0.0;
  if (!state.is_object()) throw Error("must be an object", "");
  if (!state.contains("last_increment") && !state.contains("last_length")) return;  // nothing to predict from
  if (!state.contains("last_length") || !state.at("last_length").is_number() ||
      !(state.at("last_length").get<double>() > 0.0) || !(state.at("last_length").get<double>() <= 1.0))
    throw Error("must be a number in (0, 1]", "/last_length");
  const nlohmann::json& list = state.contains("last_increment") ? state.at("last_increment") : nlohmann::json();
  if (!list.is_array() || list.size() != static_cast<size_t>(problem_->num_dofs()))
    throw Error(fmt::format("must be an array of {} numbers (3 per vertex)", problem_->num_dofs()), "/last_increment");
  Eigen::VectorXd increment(static_cast<Eigen::Index>(list.size()));
  for (size_t i = 0; i < list.size(); ++i) {
    if (!list[i].is_number() || !std::isfinite(list[i].get<double>()))
      throw Error("must be a finite number", fmt::format("/last_increment/{}", i));
    increment(static_cast<Eigen::Index>(i)) = list[i].get<double>();
  }
  last_increment_ = std::move(increment);
  last_length_ = state.at("last_length").get<double>();
}

}  // namespace sinew
