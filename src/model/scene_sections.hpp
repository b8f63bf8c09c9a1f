#pragma once
// Section parsers shared between the scene reader's source files (not a public header).
#include "sinew/motion/prescribed_motion.hpp"
#include "sinew/model/json_reader.hpp"
#include "sinew/model/scene.hpp"

namespace sinew {

// A boundary or obstacle motion ({"type": "pinned" | "translate" | "rotate" | "keyframes", ...}).
RigidMotion parse_motion(JsonObject o);

// A load or motion amplitude: "ramp" or [[frame, factor], ...] (motion/amplitude.hpp).
Amplitude parse_amplitude(JsonObject& o, const std::string& key);

// One entry of the scene's `boundary` list (scene_boundary.cpp).
BoundarySpec parse_boundary_condition(JsonObject b, VertexSelector (*parse_selector)(JsonObject));

// Sets every "ramp" amplitude of the scene to end at its last frame.
void resolve_ramps(Scene& scene);

// Reads the optional `dynamics` object and `obstacles` list of the scene root into `scene`.
void parse_dynamics_sections(JsonObject& root, Scene& scene);

}  // namespace sinew
