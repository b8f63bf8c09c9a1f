#pragma once
// Section parsers shared between the scene reader's source files (not a public header).
#include "sinew/motion/prescribed_motion.hpp"
#include "sinew/model/json_reader.hpp"
#include "sinew/model/scene.hpp"

namespace sinew {

// A boundary or obstacle motion ({"type": "pinned" | "translate" | "rotate" | "keyframes", ...}).
RigidMotion parse_motion(JsonObject o);

// Reads the optional `dynamics` object and `obstacles` list of the scene root into `scene`.
void parse_dynamics_sections(JsonObject& root, Scene& scene);

}  // namespace sinew
