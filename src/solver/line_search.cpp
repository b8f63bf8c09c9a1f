#include "sinew/solver/line_search.hpp"

#include <algorithm>
#include <cmath>

namespace sinew {

LineSearchResult backtracking_line_search(const LineSearchObjective& objective, const Eigen::VectorXd& x,
                                          const Eigen::VectorXd& d, double energy, double slope, double residual,
                                          const LineSearchSettings& s, Eigen::VectorXd& trial) {
  LineSearchResult out;
  double alpha = 1.0;
  for (int ls = 0; ls < s.max_steps; ++ls, alpha *= 0.5) {
    out.step = alpha;
    trial = x + alpha * d;
    const double trial_energy = objective.value(trial);
    ++out.evaluations;
    if (!std::isfinite(trial_energy)) continue;
    out.energy = trial_energy;
    if (trial_energy <= energy + s.armijo * alpha * slope) {
      out.accepted = true;
      return out;
    }
    // Near convergence the energy decrease drowns in rounding: accept a step that lowers the
    // residual instead.
    if (std::abs(trial_energy - energy) <= 1e-12 * std::max(1.0, std::abs(energy))) {
      if (objective.gradient(trial).norm() < residual) {
        out.accepted = true;
        return out;
      }
    }
  }
  return out;
}

}  // namespace sinew
