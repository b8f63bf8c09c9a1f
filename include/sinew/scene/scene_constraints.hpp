#pragma once
// The "constraints" scene section (docs/energy-limits.md): dynamics with paper 001's
// energy-limiting constraints and constraint contact, solved by PGS inside an SQP loop.
#include <Eigen/Core>
#include <optional>
#include <string>

#include "sinew/constraints/constrained_stepper.hpp"

namespace sinew {

class JsonObject;

struct GroundSpec {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;   // plane {p : n . p = offset}
  double margin = 0.01;  // vertices closer than this become contact candidates (m)
};

struct ConstraintsSpec {
  std::string model = "corotational";  // "corotational" (paper 001 §3) | "material" (the scene's material)
  int steps_per_frame = 1;
  Eigen::Vector3d initial_velocity = Eigen::Vector3d::Zero();
  std::optional<GroundSpec> ground;
  double friction = 0.0;
  ConstrainedStepSettings step;  // time step, energy limit, PGS and SQP settings
};

// Strict reader: unknown keys, wrong types, non-finite or out-of-range numbers are sinew::Errors
// naming the file and JSON path.
ConstraintsSpec parse_constraints(JsonObject object);

}  // namespace sinew
