#pragma once
// Runs a scene with a "constraints" section: backward-Euler dynamics with paper 001's
// energy-limiting constraints and constraint contact against the scene's obstacles,
// dynamics.substeps time steps of dynamics.time_step / substeps per frame, outputs like the quasistatic runner plus per-frame PGS/SQP figures in summary.json.
#include "sinew/run/simulation.hpp"

namespace sinew {

RunSummary run_constrained_scene(const Scene& scene, const RunOptions& options);

}  // namespace sinew
