#pragma once
// Projected Newton on the total energy with a backtracking line search (paper 000 §6,
// solver/line_search.hpp). The linear solver gets a SolverContext with the problem's
// discretisation (and lattice) and fixed-DOF mask.
#include <functional>
#include <string>

#include "sinew/solver/linear_solver.hpp"
#include "sinew/assembly/problem.hpp"

namespace sinew {

// When a solve has converged.
//  Relative (the default): dimensionless, so the same problem in other units or at another scale
//    stops at the same place. The free-DOF residual must be at most `residual_tolerance` times
//    the problem's force scale: the largest of the solve's initial residual, the largest force
//    any one energy term exerts at the current state (loads, internal forces and so the
//    reactions, inertia) and a floor of 1e-8 x stiffness x size^2 (Problem::scales). And the
//    last Newton step must be at most `step_tolerance` times the displacement of the solve so
//    far (floored at 1e-6 of the body's size per vertex): a solve never stops at its starting
//    point while a Newton step would still move it.
//  Absolute (paper 000 §6): the residual's 2-norm below `absolute_tolerance` (a force, so it
//    depends on the units), or below `relative_tolerance` x initial residual if that is set.
enum class ConvergenceTest { Relative, Absolute };

struct NewtonSettings {
  ConvergenceTest test = ConvergenceTest::Relative;
  double residual_tolerance = 1e-6;  // relative test
  double step_tolerance = 1e-4;      // relative test
  double absolute_tolerance = 1e-2;  // absolute test: ||free-DOF force residual||_2 (paper 000: 1e-2)
  double relative_tolerance = 0.0;   // absolute test, optional: also stop at residual <= rel * initial
  int max_iterations = 100;
  double linear_tolerance = 1e-4;    // relative residual for iterative linear solvers
  bool eisenstat_walker = false;     // adaptive linear tolerance (forcing term, choice 2)
  double armijo = 1e-4;            // LineSearchSettings::armijo
  int max_line_search_steps = 40;  // LineSearchSettings::max_steps
};

struct NewtonIterate {
  int iteration = 0;
  double residual = 0.0;
  double energy = 0.0;
  double step = 0.0;          // accepted line-search step length
  int linear_iterations = 0;  // in this iteration
};

struct NewtonReport {
  bool converged = false;
  int iterations = 0;
  int linear_iterations = 0;
  double initial_residual = 0.0;
  double residual = 0.0;
  double force_scale = 0.0;  // the relative test's force scale at the end (computed for either test)
  double step_norm = 0.0;    // 2-norm of the last Newton step (global coordinates)
  double energy = 0.0;
  double assembly_seconds = 0.0;
  double solve_seconds = 0.0;
  std::string failure;  // why it stopped without converging
  // The absolute tolerance is below what double precision can resolve for this problem (under
  // 1e-15 x the largest force of a form): no number of iterations or smaller steps would meet it.
  bool tolerance_unreachable = false;
};

// The test in words, for summary.json and messages.
std::string describe_convergence_test(const NewtonSettings& settings);

// The dimensionless residual residual / force_scale (the residual itself if no scale is known).
double convergence_measure(const NewtonReport& report);

NewtonReport newton_solve(Problem& problem, Eigen::VectorXd& x, LinearSolver& linear,
                          const NewtonSettings& settings,
                          const std::function<void(const NewtonIterate&)>& progress = {});

}  // namespace sinew
