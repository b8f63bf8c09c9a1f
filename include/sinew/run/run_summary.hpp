#pragma once
// summary.json: one schema for every integrator. Per frame the stats record (iterations,
// residual, times, failure), the integrator's named counters under "counters", and what was
// measured on the frame's state; per run the model, the integrator and the totals.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "sinew/model/model.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {

nlohmann::json frame_to_json(const FrameRecord& record);
FrameRecord frame_from_json(const nlohmann::json& json);  // throws nlohmann::json exceptions

// Writes out/summary.json atomically.
void write_summary(const std::filesystem::path& out, const Scene& scene, const Model& model,
                   const RunSummary& summary, int frames_requested);

}  // namespace sinew
