#include "sinew/integrator/integrator.hpp"

#include <algorithm>

namespace sinew {

void StepStats::add_counter(const std::string& name, double value) {
  for (Counter& c : counters)
    if (c.name == name) {
      c.value += value;
      return;
    }
  counters.push_back({name, value, false});
}

void StepStats::max_counter(const std::string& name, double value) {
  for (Counter& c : counters)
    if (c.name == name) {
      c.value = std::max(c.value, value);
      return;
    }
  counters.push_back({name, value, true});
}

double StepStats::counter(const std::string& name) const {
  for (const Counter& c : counters)
    if (c.name == name) return c.value;
  return 0.0;
}

void StepStats::accumulate(const StepStats& part) {
  newton_iterations += part.newton_iterations;
  linear_iterations += part.linear_iterations;
  substeps += part.substeps;
  residual = part.residual;
  force_scale = part.force_scale;
  energy = part.energy;
  seconds += part.seconds;
  assembly_seconds += part.assembly_seconds;
  solve_seconds += part.solve_seconds;
  if (!part.converged) converged = false;
  if (failure.empty()) failure = part.failure;
  for (const Counter& c : part.counters) c.maximum ? max_counter(c.name, c.value) : add_counter(c.name, c.value);
}

}  // namespace sinew
