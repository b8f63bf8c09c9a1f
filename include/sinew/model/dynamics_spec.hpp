#pragma once
// The scene's `dynamics` section (implicit time stepping) and `obstacles` list (rigid shapes
// on rigid paths, penalty contact), docs/dynamics.md.
#include <Eigen/Core>
#include <memory>
#include <string>

#include "sinew/motion/obstacle.hpp"
#include "sinew/forms/penalty_contact_form.hpp"
#include "sinew/forms/inertia_form.hpp"
#include "sinew/integrator/time_stepper.hpp"

namespace sinew {

struct DynamicsSpec {
  double time_step = 0.0;  // seconds per frame
  int substeps = 1;        // time steps per frame (h = time_step / substeps)
  DynamicsScheme integrator = DynamicsScheme::BackwardEuler;
  MassKind mass = MassKind::Lumped;
  double rayleigh_alpha = 0.0, rayleigh_beta = 0.0;  // D = alpha M + beta K
  Eigen::Vector3d initial_velocity = Eigen::Vector3d::Zero();
  double friction_velocity = 1e-2;  // m/s: slip speed below which friction sticks
};

struct ObstacleSpec {
  std::string name;
  std::shared_ptr<const ObstacleShape> shape;
  RigidMotion motion;  // of the frame number, like boundary motions
  ContactParameters contact;
};

}  // namespace sinew
