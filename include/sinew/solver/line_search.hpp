#pragma once
// Backtracking line search along a descent direction (Armijo sufficient decrease), the Newton
// solver's safeguard, on its own so that other nonlinear solvers (and tests) can use it.
#include <Eigen/Core>
#include <functional>

namespace sinew {

struct LineSearchSettings {
  double armijo = 1e-4;  // sufficient-decrease constant c in E(x + a d) <= E(x) + c a g.d
  int max_steps = 40;    // trial step lengths 1, 1/2, 1/4, ...
};

// The energy (non-finite outside its domain) and its gradient, the latter used only near
// convergence where energy differences drown in rounding.
struct LineSearchObjective {
  std::function<double(const Eigen::VectorXd&)> value;
  std::function<Eigen::VectorXd(const Eigen::VectorXd&)> gradient;
};

struct LineSearchResult {
  bool accepted = false;
  double step = 0.0;    // the accepted step length (the last one tried when not accepted)
  double energy = 0.0;  // energy at the accepted point
  int evaluations = 0;  // energy evaluations
};

// Tries x + a d for a = 1, 1/2, ... up to settings.max_steps times and accepts the first a with
// E(x + a d) <= energy + armijo a slope (slope = g.d < 0), or, when |E(x + a d) - energy| is
// below 1e-12 max(1, |energy|), one whose gradient norm is below `residual` (= |g(x)|). The
// accepted point is left in `trial`.
LineSearchResult backtracking_line_search(const LineSearchObjective& objective, const Eigen::VectorXd& x,
                                          const Eigen::VectorXd& d, double energy, double slope, double residual,
                                          const LineSearchSettings& settings, Eigen::VectorXd& trial);

}  // namespace sinew
