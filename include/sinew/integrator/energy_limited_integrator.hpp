#pragma once
// Energy-limited dynamics (paper 001) as an integrator: a frame is `steps_per_frame` steps of
// the energy-limited stepper, with prescribed vertices (boundary conditions, bones) moving to
// their positions at each step's end.
#include <memory>

#include "sinew/integrator/energy_limited_stepper.hpp"
#include "sinew/integrator/integrator.hpp"

namespace sinew {

class EnergyLimitedIntegrator final : public Integrator {
 public:
  EnergyLimitedIntegrator(std::unique_ptr<EnergyLimitedStepper> stepper, PrescribedMotion motion, int steps_per_frame);

  std::string name() const override { return "energy_limited"; }
  std::string description() const override { return "constrained dynamics (energy limits and constraint contact, paper 001)"; }
  bool dynamic() const override { return true; }
  std::string convergence_test() const override;
  double frame_duration() const override { return stepper_->settings().time_step * steps_per_frame_; }
  // Counters: sqp_iterations, pgs_iterations, splitting_iterations, factorizations,
  // cg_iterations (summed over the steps); max_sqp_iterations_per_step, max_pgs_residual,
  // max_energy_violation, max_penetration, max_active_energy_constraints, max_active_contacts,
  // max_element_energy (maxima). The residual is max(energy violation, penetration); the energy
  // is the elastic energy at the frame's end.
  StepStats advance_frame(State& state, int frame, const IterationProgress& progress) override;

  // The multipliers of the last LCP (the next step's warm start).
  nlohmann::json checkpoint_state() const override;
  void restore_state(const nlohmann::json& state, int frame) override;

  const EnergyLimitedStepper& stepper() const { return *stepper_; }

 private:
  std::unique_ptr<EnergyLimitedStepper> stepper_;
  PrescribedMotion motion_;
  int steps_per_frame_;
};

}  // namespace sinew
