#include "sinew/solver/newton.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "sinew/solver/line_search.hpp"

namespace sinew {
namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

constexpr double kForceFloor = 1e-8;  // x Problem::Scales::force
constexpr double kLengthFloor = 1e-6;  // x Problem::Scales::length per vertex
constexpr double kRoundOff = 1e-15;    // relative resolution of a residual (double precision)

// The convergence test of NewtonSettings (see there).
struct ConvergenceCheck {
  const NewtonSettings& s;
  const Problem& problem;
  double initial_residual = 0.0;
  Eigen::VectorXd x_start;

  double force_scale(double state_force_scale) const {
    return std::max({initial_residual, state_force_scale, kForceFloor * problem.scales().force});
  }
  // `step_norm` < 0: no Newton step taken yet.
  bool passed(double residual, double state_force_scale, const Eigen::VectorXd& x, double step_norm) const {
    if (s.test == ConvergenceTest::Absolute)
      return residual < s.absolute_tolerance ||
             (s.relative_tolerance > 0.0 && residual <= s.relative_tolerance * initial_residual);
    const double floor = kForceFloor * problem.scales().force;
    if (residual == 0.0 || residual <= s.residual_tolerance * floor) return true;  // nothing left to do
    if (!(residual <= s.residual_tolerance * force_scale(state_force_scale))) return false;
    if (step_norm < 0.0) return false;  // one Newton step shows whether the start is equilibrium
    const double vertices = static_cast<double>(problem.num_dofs()) / 3.0;
    const double moved = std::max((x - x_start).norm(), kLengthFloor * problem.scales().length * std::sqrt(vertices));
    return step_norm <= s.step_tolerance * moved;
  }
};
std::string describe_residual(const NewtonReport& r) {
  if (r.force_scale <= 0.0) return fmt::format("residual {:.3e}", r.residual);
  return fmt::format("residual {:.3e} = {:.2e} of the force scale {:.3e}", r.residual, r.residual / r.force_scale,
                     r.force_scale);
}
}  // namespace

std::string describe_convergence_test(const NewtonSettings& s) {
  if (s.test == ConvergenceTest::Absolute)
    return s.relative_tolerance > 0.0
               ? fmt::format("absolute: residual < {:g} or <= {:g} x initial residual", s.absolute_tolerance,
                             s.relative_tolerance)
               : fmt::format("absolute: residual < {:g}", s.absolute_tolerance);
  return fmt::format("relative: residual <= {:g} x force scale and Newton step <= {:g} x displacement",
                     s.residual_tolerance, s.step_tolerance);
}

double convergence_measure(const NewtonReport& r) {
  return r.force_scale > 0.0 ? r.residual / r.force_scale : r.residual;
}

NewtonReport newton_solve(Problem& problem, Eigen::VectorXd& x, LinearSolver& linear,
                          const NewtonSettings& s,
                          const std::function<void(const NewtonIterate&)>& progress, const Eigen::VectorXd* origin) {
  NewtonReport report;
  if (!problem.is_valid(x)) {
    report.failure = "initial state is outside the energy's domain (e.g. inverted elements of a "
                     "log-based material)";
    return report;
  }
  auto t0 = std::chrono::steady_clock::now();
  problem.begin_solve(x);
  double state_scale = 0.0;
  Eigen::VectorXd g = problem.gradient(x, state_scale);
  double energy = problem.value(x);
  report.assembly_seconds += seconds_since(t0);
  double residual = g.norm();
  report.initial_residual = residual;
  ConvergenceCheck check{s, problem, residual, origin && origin->size() == x.size() ? *origin : x};
  double step_norm = -1.0;
  double eta = s.linear_tolerance, previous_residual = residual;
  Eigen::VectorXd d, trial;
  const LineSearchObjective objective{[&](const Eigen::VectorXd& y) { return problem.value(y); },
                                      [&](const Eigen::VectorXd& y) { return problem.gradient(y); }};
  const LineSearchSettings line_search{s.armijo, s.max_line_search_steps};
  // What the linear solver and its preconditioner may use besides the matrix; the fixed mask is
  // the problem's own (set before the solve, unchanged during it).
  const SolverContext context{problem.discretization(), problem.fixed()};
  SolverContext exact_context = context;
  exact_context.may_be_indefinite = true;
  bool try_exact = false;
  double retry_below = std::numeric_limits<double>::infinity();
  for (int it = 0;; ++it) {
    report.iterations = it;
    report.residual = residual;
    report.energy = energy;
    report.force_scale = check.force_scale(state_scale);
    report.step_norm = std::max(step_norm, 0.0);
    if (check.passed(residual, state_scale, x, step_norm)) {
      // Lagged terms (contacts) are refreshed (refitted, dropped) only at a converged state, never
      // at the distorted iterates on the way there, and Newton goes on if they changed the energy.
      t0 = std::chrono::steady_clock::now();
      const bool changed = problem.refresh(x);
      if (changed) {
        g = problem.gradient(x, state_scale);
        energy = problem.value(x);
        residual = g.norm();
      }
      report.assembly_seconds += seconds_since(t0);
      report.residual = residual;
      report.energy = energy;
      report.force_scale = check.force_scale(state_scale);
      if (!changed || check.passed(residual, state_scale, x, step_norm)) {
        report.converged = true;
        return report;
      }
    }
    if (it >= s.max_iterations) {
      report.failure = fmt::format("no convergence in {} Newton iterations ({})", it, describe_residual(report));
      if (s.test == ConvergenceTest::Absolute && s.absolute_tolerance < kRoundOff * state_scale) {
        report.tolerance_unreachable = true;
        report.failure += fmt::format("; the tolerance {:g} is below round-off for forces of {:.3e}", s.absolute_tolerance,
                                      state_scale);
      }
      return report;
    }
    if (s.eisenstat_walker && it > 0) {
      // Eisenstat-Walker choice 2 with the usual safeguard.
      const double ratio = residual / previous_residual;
      eta = std::clamp(std::max(0.9 * ratio * ratio, 0.9 * eta * eta), 1e-8, 0.5);
    }
    // The true Hessian first when the tail has begun; the projected one otherwise or if it fails.
    bool exact = false;
    int linear_iterations = 0;
    if (try_exact) {
      t0 = std::chrono::steady_clock::now();
      const LinearOperator& H = problem.hessian(x, true);
      report.assembly_seconds += seconds_since(t0);
      t0 = std::chrono::steady_clock::now();
      const LinearSolveReport lin = linear.solve(H, -g, d, eta, exact_context);
      report.solve_seconds += seconds_since(t0);
      report.linear_iterations += lin.iterations;
      linear_iterations = lin.iterations;
      exact = lin.converged && d.allFinite() && g.dot(d) < 0.0;
      if (!exact) {
        ++report.exact_fallbacks;
        try_exact = false;
        retry_below = 0.1 * residual;
      }
    }
    if (!exact) {
      t0 = std::chrono::steady_clock::now();
      const LinearOperator& H = problem.hessian(x);
      report.assembly_seconds += seconds_since(t0);
      t0 = std::chrono::steady_clock::now();
      const LinearSolveReport lin = linear.solve(H, -g, d, eta, context);
      report.solve_seconds += seconds_since(t0);
      report.linear_iterations += lin.iterations;
      linear_iterations += lin.iterations;
    } else {
      ++report.exact_iterations;
    }

    // A direction that does not descend (failed or inexact solve) falls back to -g. Both are in
    // the problem's local DOFs (rotated vertex frames), where the slope is the same.
    double slope = g.dot(d);
    bool newton_direction = true;
    if (!d.allFinite() || !(slope < 0.0)) {
      d = -g;
      slope = -g.squaredNorm();
      newton_direction = false;
    }
    problem.to_global(d);
    t0 = std::chrono::steady_clock::now();
    const LineSearchResult step = backtracking_line_search(objective, x, d, energy, slope, residual, line_search, trial);
    report.assembly_seconds += seconds_since(t0);
    if (!step.accepted) {
      report.failure = fmt::format("line search failed at Newton iteration {} ({})", it, describe_residual(report));
      return report;
    }
    x = trial;
    energy = step.energy;
    previous_residual = residual;
    // A gradient step is no measure of the distance to equilibrium: the step test waits for a
    // Newton step.
    step_norm = newton_direction ? d.norm() : std::numeric_limits<double>::infinity();
    t0 = std::chrono::steady_clock::now();
    if (problem.add_at_iterate(x)) energy = problem.value(x);  // terms added (self-contact samples)
    g = problem.gradient(x, state_scale);
    report.assembly_seconds += seconds_since(t0);
    residual = g.norm();
    if (s.exact_tail) {
      if (exact) {
        if (step.step < 1.0) {  // the quadratic model was poor: back to the projection
          ++report.exact_short_steps;
          try_exact = false;
          retry_below = 0.1 * residual;
        }
      } else {
        // After a fallback, the next try waits until the residual has dropped tenfold.
        try_exact = report.exact_fallbacks + report.exact_short_steps < kMaxExactFallbacks && newton_direction && step.step == 1.0 &&
                    residual < previous_residual && residual < retry_below;
      }
    }
    if (progress) progress({it + 1, residual, energy, step.step, linear_iterations});
  }
}

}  // namespace sinew
