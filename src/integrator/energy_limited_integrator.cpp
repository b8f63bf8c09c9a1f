#include "sinew/integrator/energy_limited_integrator.hpp"

#include <fmt/format.h>
#include <cmath>

#include "sinew/core/error.hpp"

namespace sinew {

EnergyLimitedIntegrator::EnergyLimitedIntegrator(std::unique_ptr<EnergyLimitedStepper> stepper,
                                                 PrescribedMotion motion, int steps_per_frame)
    : stepper_(std::move(stepper)), motion_(std::move(motion)), steps_per_frame_(steps_per_frame) {}

std::string EnergyLimitedIntegrator::convergence_test() const {
  const EnergyLimitedStepSettings& s = stepper_->settings();
  return fmt::format("SQP per time step: every element energy <= (1 + {:g}) x its limit and obstacle penetration <= "
                     "{:g} (a length), within {} SQP iterations",
                     s.energy_tolerance, s.contact_tolerance, s.sqp_max_iterations);
}

StepStats EnergyLimitedIntegrator::advance_frame(State& state, int frame, const IterationProgress& progress) {
  const EnergyLimitedStepSettings& settings = stepper_->settings();
  StepStats stats;
  EnergyLimitedStepTotals totals;
  const int n = steps_per_frame_;
  for (int s = 1; s <= n; ++s) {
    const double frame1 = frame - 1 + double(s) / n;
    Eigen::VectorXd x_end = state.x;
    std::vector<char> fixed(static_cast<size_t>(state.x.size()), 0);
    if (motion_) motion_(frame1, x_end, fixed);
    const EnergyLimitedStepReport r = stepper_->step(state.x, state.v, fixed, x_end);
    totals.add(r);
    stats.substeps += 1;
    if (progress) progress(s, std::max(r.energy_violation, r.penetration));
    if (!r.converged && stats.failure.empty())
      stats.failure = fmt::format(
          "step {} of the frame: SQP stopped after {} iteration(s) with energy violation {:.3e} (tolerance {:.1e}), "
          "penetration {:.3e} m (tolerance {:.1e}), PGS residual {:.3e} (tolerance {:.1e})",
          s, r.sqp_iterations, r.energy_violation, settings.energy_tolerance, r.penetration,
          settings.contact_tolerance, r.pgs_residual, settings.pgs.tolerance);
  }
  stats.converged = stats.failure.empty();
  stats.residual = std::max(totals.max_energy_violation, totals.max_penetration);
  stats.energy = stepper_->limited_form().value(state.x);
  stats.solve_seconds = totals.seconds;
  stats.add_counter("sqp_iterations", totals.sqp_iterations);
  stats.add_counter("pgs_iterations", totals.pgs_iterations);
  stats.add_counter("splitting_iterations", totals.splitting_iterations);
  stats.add_counter("factorizations", totals.factorizations);
  stats.add_counter("cg_iterations", totals.cg_iterations);
  stats.max_counter("max_sqp_iterations_per_step", totals.max_sqp_iterations);
  stats.max_counter("max_pgs_residual", totals.max_pgs_residual);
  stats.max_counter("max_energy_violation", totals.max_energy_violation);
  stats.max_counter("max_penetration", totals.max_penetration);
  stats.max_counter("max_active_energy_constraints", totals.max_active_energy);
  stats.max_counter("max_active_contacts", totals.max_active_contacts);
  stats.max_counter("max_element_energy", totals.max_element_energy);
  return stats;
}

nlohmann::json EnergyLimitedIntegrator::checkpoint_state() const {
  nlohmann::json multipliers = nlohmann::json::array();
  for (const auto& [key, value] : stepper_->multipliers()) multipliers.push_back({key, value});
  nlohmann::json state = {{"multipliers", multipliers}};
  // The SQP predictor and the last step's correction (per DOF), where the last step left them.
  for (const auto& [key, values] : {std::pair<const char*, const Eigen::VectorXd*>{"predictor", &stepper_->predictor()},
                                    {"correction", &stepper_->correction()}})
    if (values->size() > 0) state[key] = std::vector<double>(values->data(), values->data() + values->size());
  return state;
}

void EnergyLimitedIntegrator::restore_state(const nlohmann::json& state, int frame) {
  // Keys index the constraints (stepper: an element's energy row is its index e >= 0, a contact
  // row -1 - 3 vertex - s): a key past the mesh would index past its elements.
  const Discretization& disc = stepper_->limited_form().discretization();
  const long elements = static_cast<long>(disc.num_elements());
  const long lowest_key = -static_cast<long>(disc.num_dofs());  // -1 - 3 (V - 1) - 2
  if (!state.is_object() || !state.contains("multipliers") || !state.at("multipliers").is_array())
    throw Error("must hold the array \"multipliers\"", "");
  std::map<long, double> multipliers;
  const nlohmann::json& list = state.at("multipliers");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const nlohmann::json& m = list[i];
    const std::string where = fmt::format("/multipliers/{}", i);
    if (!m.is_array() || m.size() != 2 || !m[0].is_number_integer() || !m[1].is_number())
      throw Error("must be a [constraint key, multiplier] pair of a whole number and a number", where);
    const long key = m[0].get<long>();
    if (key < lowest_key || key >= elements)
      throw Error(fmt::format("constraint key {} is outside the mesh's range {} to {}", key, lowest_key, elements - 1), where);
    multipliers[key] = m[1].get<double>();
  }
  stepper_->set_multipliers(std::move(multipliers));
  // Optional (checkpoints written before the predictor have none: the first resumed step then
  // starts without a prediction; before the correction, without an extrapolation).
  auto per_dof = [&](const char* key) {
    Eigen::VectorXd values;
    if (!state.contains(key)) return values;
    const nlohmann::json& p = state.at(key);
    const std::string where = std::string("/") + key;
    if (!p.is_array() || p.size() != static_cast<std::size_t>(disc.num_dofs()))
      throw Error(fmt::format("must be an array of {} numbers (one per DOF)", disc.num_dofs()), where);
    values.resize(disc.num_dofs());
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!p[i].is_number() || !std::isfinite(p[i].get<double>()))
        throw Error("must be a finite number", fmt::format("{}/{}", where, i));
      values(static_cast<Eigen::Index>(i)) = p[i].get<double>();
    }
    return values;
  };
  stepper_->set_predictor(per_dof("predictor"));
  stepper_->set_correction(per_dof("correction"));
  stepper_->set_time(frame * frame_duration());
}

}  // namespace sinew
