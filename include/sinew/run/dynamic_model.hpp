#pragma once
// What a scene's `dynamics` section and `obstacles` add to the quasistatic model: penalty
// contact (both modes), inertia, damping and the time stepper (dynamics only), and how
// run_scene advances a dynamic frame.
#include <functional>
#include <memory>

#include "sinew/run/simulation.hpp"
#include "sinew/integrator/time_stepper.hpp"

namespace sinew {

struct DynamicModel {
  std::shared_ptr<PenaltyContactForm> contact;  // null without obstacles
  std::shared_ptr<MassMatrix> mass;             // the rest: dynamics only
  std::shared_ptr<InertiaForm> inertia;
  std::shared_ptr<DampingForm> damping;         // null without Rayleigh damping
  std::unique_ptr<TimeStepper> stepper;
  Eigen::VectorXd v;  // velocities
  bool dynamic() const { return stepper != nullptr; }
};

// Adds the forms of the scene's obstacles and dynamics to `problem`.
DynamicModel build_dynamic_model(const Scene& scene, const std::shared_ptr<const Discretization>& disc,
                                 const std::shared_ptr<const Form>& elastic, const BoundarySurface& surface,
                                 Problem& problem, const std::vector<KinematicCondition>& kinematics);

// Advances x and the model's velocities over frame `frame` (from frame - 1) in
// dynamics.substeps time steps, accumulating iterations and timings in `record` and setting
// its failure if a step fails (x is then the last completed step's state).
void advance_dynamic_frame(DynamicModel& model, const Scene& scene, Eigen::VectorXd& x, int frame,
                           LinearSolver& linear, FrameRecord& record,
                           const std::function<void(const NewtonIterate&)>& progress);

// Kinetic and potential (elastic + external + contact penalty) energy and contact counts of x.
void record_energies(const DynamicModel& model, const Form& elastic, const Eigen::VectorXd& forces,
                     const Eigen::VectorXd& x, FrameRecord& record);

}  // namespace sinew
