#include "sinew/solver/newton.hpp"

#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "sinew/solver/line_search.hpp"

namespace sinew {
namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

NewtonReport newton_solve(Problem& problem, Eigen::VectorXd& x, LinearSolver& linear,
                          const NewtonSettings& s,
                          const std::function<void(const NewtonIterate&)>& progress) {
  NewtonReport report;
  if (!problem.is_valid(x)) {
    report.failure = "initial state is outside the energy's domain (e.g. inverted elements of a "
                     "log-based material)";
    return report;
  }
  auto t0 = std::chrono::steady_clock::now();
  problem.begin_solve(x);
  Eigen::VectorXd g = problem.gradient(x);
  double energy = problem.value(x);
  report.assembly_seconds += seconds_since(t0);
  double residual = g.norm();
  report.initial_residual = residual;
  double eta = s.linear_tolerance, previous_residual = residual;
  Eigen::VectorXd d, trial;
  const LineSearchObjective objective{[&](const Eigen::VectorXd& y) { return problem.value(y); },
                                      [&](const Eigen::VectorXd& y) { return problem.gradient(y); }};
  const LineSearchSettings line_search{s.armijo, s.max_line_search_steps};
  // What the linear solver and its preconditioner may use besides the matrix; the fixed mask is
  // the problem's own (set before the solve, unchanged during it).
  const SolverContext context{problem.discretization(), problem.fixed()};
  for (int it = 0;; ++it) {
    report.iterations = it;
    report.residual = residual;
    report.energy = energy;
    const bool abs_ok = residual < s.absolute_tolerance;
    const bool rel_ok = s.relative_tolerance > 0.0 && residual <= s.relative_tolerance * report.initial_residual;
    if (abs_ok || rel_ok) {
      // Lagged terms (contacts) are updated only at a converged state, never at the distorted
      // iterates on the way there, and Newton goes on if they changed the energy.
      t0 = std::chrono::steady_clock::now();
      const bool changed = problem.refresh(x);
      if (changed) {
        g = problem.gradient(x);
        energy = problem.value(x);
        residual = g.norm();
      }
      report.assembly_seconds += seconds_since(t0);
      report.residual = residual;
      report.energy = energy;
      if (!changed || residual < s.absolute_tolerance) {
        report.converged = true;
        return report;
      }
    }
    if (it >= s.max_iterations) {
      report.failure = fmt::format("no convergence in {} Newton iterations (residual {:.3e})", it, residual);
      return report;
    }
    t0 = std::chrono::steady_clock::now();
    const LinearOperator& H = problem.hessian(x);
    report.assembly_seconds += seconds_since(t0);

    if (s.eisenstat_walker && it > 0) {
      // Eisenstat-Walker choice 2 with the usual safeguard.
      const double ratio = residual / previous_residual;
      eta = std::clamp(std::max(0.9 * ratio * ratio, 0.9 * eta * eta), 1e-8, 0.5);
    }
    t0 = std::chrono::steady_clock::now();
    const LinearSolveReport lin = linear.solve(H, -g, d, eta, context);
    report.solve_seconds += seconds_since(t0);
    report.linear_iterations += lin.iterations;

    // A direction that does not descend (failed or inexact solve) falls back to -g.
    double slope = g.dot(d);
    if (!d.allFinite() || !(slope < 0.0)) {
      d = -g;
      slope = -g.squaredNorm();
    }
    t0 = std::chrono::steady_clock::now();
    const LineSearchResult step = backtracking_line_search(objective, x, d, energy, slope, residual, line_search, trial);
    report.assembly_seconds += seconds_since(t0);
    if (!step.accepted) {
      report.failure = fmt::format("line search failed at Newton iteration {} (residual {:.3e})", it, residual);
      return report;
    }
    x = trial;
    energy = step.energy;
    previous_residual = residual;
    t0 = std::chrono::steady_clock::now();
    g = problem.gradient(x);
    report.assembly_seconds += seconds_since(t0);
    residual = g.norm();
    if (progress) progress({it + 1, residual, energy, step.step, lin.iterations});
  }
}

}  // namespace sinew
