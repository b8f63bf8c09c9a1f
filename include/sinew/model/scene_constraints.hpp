#pragma once
// The "constraints" scene section (docs/energy-limits.md): dynamics with paper 001's
// energy-limiting constraints and constraint contact, solved by PGS inside an SQP loop.
#include <Eigen/Core>
#include <optional>
#include <string>

#include "sinew/integrator/energy_limited_stepper.hpp"

namespace sinew {

class JsonObject;

// Only what is specific to paper 001: the time step, substeps and initial velocity come from the
// scene's `dynamics` section and the contact geometry and friction from its `obstacles`.
struct ConstraintsSpec {
  std::string model = "corotational";  // "corotational" (paper 001 §3) | "material" (the scene's material)
  double contact_margin = 0.01;  // boundary vertices closer than this to an obstacle become candidates (m)
  EnergyLimitedStepSettings step;  // energy limit, PGS and SQP settings; time_step = dynamics h
};

// Strict reader: unknown keys, wrong types, non-finite or out-of-range numbers are sinew::Errors
// naming the file and JSON path. Keys that moved to `dynamics` / `obstacles` say where.
ConstraintsSpec parse_constraints(JsonObject object);

}  // namespace sinew
