#pragma once
// Implicit time integration over the forms of a Problem (elastic, external, inertia, damping,
// contact): each step minimises the incremental potential with the same projected Newton as the
// quasistatic solve. Backward Euler runs Newton to tolerance; the semi-implicit mode
// (Baraff-Witkin 1998, as paper 000's drop test used) takes exactly one Newton step per step.
// Kinematic boundary conditions and obstacles are placed at the step's end time.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sinew/forms/penalty_contact_form.hpp"
#include "sinew/forms/inertia_form.hpp"
#include "sinew/motion/prescribed_motion.hpp"
#include "sinew/integrator/integrator.hpp"
#include "sinew/solver/newton.hpp"

namespace sinew {

enum class DynamicsScheme { BackwardEuler, SemiImplicit };
const char* to_string(DynamicsScheme scheme);

struct TimeStepSettings {
  DynamicsScheme integrator = DynamicsScheme::BackwardEuler;
  NewtonSettings newton;
  double friction_velocity = 1e-2;  // IPC's eps_v: slip speed below which friction sticks (m/s)
};

class TimeStepper {
 public:
  // `problem` must already hold `inertia` and, where given, `damping` and `contact`.
  TimeStepper(Problem& problem, std::shared_ptr<InertiaForm> inertia, std::shared_ptr<DampingForm> damping,
              std::shared_ptr<PenaltyContactForm> contact, std::vector<KinematicCondition> kinematics,
              Eigen::MatrixX3d rest, TimeStepSettings settings);

  double time_step() const { return inertia_->time_step(); }
  const TimeStepSettings& settings() const { return settings_; }

  // Kinematic conditions beyond the rigid ones (e.g. rig bones): called after them with the
  // step's end frame, the rest positions, the trial positions and the fixed-DOF flags, and
  // free to move vertices and fix their DOFs (a later condition wins on a shared vertex).
  using KinematicHook =
      std::function<void(double frame, const Eigen::MatrixX3d& rest, Eigen::VectorXd& x, std::vector<char>& fixed)>;
  void add_kinematic_hook(KinematicHook hook) { hooks_.push_back(std::move(hook)); }

  // Advances positions x and velocities v by one time step, from frame0 to frame1 (fractional
  // frame numbers: what boundary motions and obstacle paths are functions of). On failure x
  // and v are left at the step's start.
  StepStats step(Eigen::VectorXd& x, Eigen::VectorXd& v, double frame0, double frame1, LinearSolver& linear,
                  const std::function<void(const NewtonIterate&)>& progress = {});

 private:
  Problem& problem_;
  std::shared_ptr<InertiaForm> inertia_;
  std::shared_ptr<DampingForm> damping_;
  std::shared_ptr<PenaltyContactForm> contact_;
  std::vector<KinematicCondition> kinematics_;
  std::vector<KinematicHook> hooks_;
  Eigen::MatrixX3d rest_;
  TimeStepSettings settings_;
};

}  // namespace sinew
