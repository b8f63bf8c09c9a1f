#pragma once
// selections.json (scene "output": {"selections": true}): the vertices each boundary condition
// and each load selects, so a selector can be checked before trusting a run's answer.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "sinew/model/model.hpp"

namespace sinew {

// {"boundary": [{"name", "path", "vertices"}], "loads": [{"path", "vertices"[, "faces"]}]}:
// vertex ids are 0-based, as in the .vtu; face loads (traction, pressure) also list the
// boundary faces they act on (all of whose vertices are selected).
nlohmann::json selections_json(const Scene& scene, const Model& model);
void write_selections(const std::filesystem::path& path, const Scene& scene, const Model& model);

}  // namespace sinew
