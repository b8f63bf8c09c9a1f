#pragma once
// Rig files (JSON, docs/rig-format.md). Strict: unknown keys, wrong types, NaN, unsorted keys
// and out-of-range values are rejected with the file and JSON path.
#include <filesystem>
#include <nlohmann/json_fwd.hpp>

#include "sinew/motion/rig.hpp"

namespace sinew {

class JsonObject;

Rig load_rig(const std::filesystem::path& file);
// `file` names the source in errors and resolves relative paths; `path` is the JSON pointer of
// the rig object inside it ("" for a rig file, "/rig" for a rig inline in a scene).
Rig parse_rig(const nlohmann::json& json, const std::filesystem::path& file, const std::string& path = "");
Rig parse_rig(JsonObject& object);

}  // namespace sinew
