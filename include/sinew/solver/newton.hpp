#pragma once
// Projected Newton on the total energy with a backtracking line search (paper 000 §6).
#include <functional>
#include <string>

#include "sinew/solver/linear_solver.hpp"
#include "sinew/assembly/problem.hpp"

namespace sinew {

struct NewtonSettings {
  double absolute_tolerance = 1e-2;  // ||free-DOF force residual||_2 (paper 000 uses 1e-2)
  double relative_tolerance = 0.0;   // optional: also stop when residual <= rel * initial
  int max_iterations = 100;
  double linear_tolerance = 1e-4;    // relative residual for iterative linear solvers
  bool eisenstat_walker = false;     // adaptive linear tolerance (forcing term, choice 2)
  double armijo = 1e-4;
  int max_line_search_steps = 40;
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
  double energy = 0.0;
  double assembly_seconds = 0.0;
  double solve_seconds = 0.0;
  std::string failure;  // why it stopped without converging
};

NewtonReport newton_solve(Problem& problem, Eigen::VectorXd& x, LinearSolver& linear,
                          const NewtonSettings& settings,
                          const std::function<void(const NewtonIterate&)>& progress = {});

}  // namespace sinew
