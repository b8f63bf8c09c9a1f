#pragma once
// Backward Euler or semi-implicit dynamics (time_stepper.hpp) as an integrator: a frame is
// `substeps` time steps of the incremental potential.
#include <memory>

#include "sinew/integrator/integrator.hpp"
#include "sinew/integrator/time_stepper.hpp"

namespace sinew {

class ImplicitDynamicsIntegrator final : public Integrator {
 public:
  // `problem` holds every form of the incremental potential (the stepper refers to it).
  ImplicitDynamicsIntegrator(std::shared_ptr<Problem> problem, std::unique_ptr<TimeStepper> stepper,
                             std::unique_ptr<LinearSolver> linear, DynamicsScheme scheme, int substeps);

  std::string name() const override { return to_string(scheme_); }
  std::string description() const override;
  bool dynamic() const override { return true; }
  std::string convergence_test() const override;
  double frame_duration() const override { return stepper_->time_step() * substeps_; }
  StepStats advance_frame(State& state, int frame, const IterationProgress& progress) override;

 private:
  std::shared_ptr<Problem> problem_;
  std::unique_ptr<TimeStepper> stepper_;
  std::unique_ptr<LinearSolver> linear_;
  DynamicsScheme scheme_;
  int substeps_;
};

}  // namespace sinew
