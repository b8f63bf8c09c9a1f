// The scene's boundary conditions (all coordinates, some, or one direction) and the amplitudes
// of loads and motions.
#include <fmt/format.h>

#include "scene_sections.hpp"
#include "sinew/core/error.hpp"

namespace sinew {

Amplitude parse_amplitude(JsonObject& o, const std::string& key) {
  const nlohmann::json& j = o.raw(key);
  const std::string where = o.file() + ": " + o.path_of(key);
  if (j.is_string()) {
    if (j.get<std::string>() != "ramp")
      o.fail(key, fmt::format("unknown value '{}' (expected \"ramp\" or a list of [frame, factor] points)", j.get<std::string>()));
    Amplitude a;
    a.ramp_to_last_frame = true;
    return a;
  }
  if (!j.is_array() || j.empty()) o.fail(key, "must be \"ramp\" or a non-empty list of [frame, factor] points");
  Amplitude a;
  for (size_t i = 0; i < j.size(); ++i) {
    const nlohmann::json& p = j[i];
    const std::string at = fmt::format("{}/{}", key, i);
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      o.fail(at, "must be a [frame, factor] pair of numbers");
    a.points.emplace_back(p[0].get<double>(), p[1].get<double>());
  }
  validate_amplitude(a, where);
  return a;
}

BoundarySpec parse_boundary_condition(JsonObject b, VertexSelector (*parse_selector)(JsonObject)) {
  b.allow({"name", "select", "motion", "components", "direction"});
  BoundarySpec spec;
  spec.name = b.string("name", b.path());
  spec.select = parse_selector(b.object("select"));
  spec.motion = b.has("motion") ? parse_motion(b.object("motion")) : RigidMotion{Pinned{}};
  if (b.has("components") && b.has("direction")) b.fail("direction", "give either components or direction, not both");
  if (b.has("components")) {
    const nlohmann::json& c = b.raw("components");
    if (!c.is_array() || c.empty()) b.fail("components", "must be a non-empty list of \"x\", \"y\", \"z\"");
    spec.components = {false, false, false};
    for (size_t i = 0; i < c.size(); ++i) {
      const std::string at = fmt::format("components/{}", i);
      if (!c[i].is_string()) b.fail(at, "must be \"x\", \"y\" or \"z\"");
      const std::string name = c[i].get<std::string>();
      if (name != "x" && name != "y" && name != "z") b.fail(at, fmt::format("unknown component '{}' (expected x, y or z)", name));
      const int axis = name[0] - 'x';
      if (spec.components[axis]) b.fail(at, fmt::format("component '{}' is listed twice", name));
      spec.components[axis] = true;
    }
  }
  if (b.has("direction")) {
    const Eigen::Vector3d n = b.vec3("direction");
    if (!(n.norm() > 0.0)) b.fail("direction", "must be non-zero");
    spec.direction = n.normalized();
  }
  b.finish();
  return spec;
}

namespace {
void resolve_motion_ramp(RigidMotion& motion, double last_frame) {
  if (auto* d = std::get_if<Displacement>(&motion)) d->amplitude.resolve_ramp(last_frame);
}
}  // namespace

void resolve_ramps(Scene& scene) {
  const double last = scene.frames;
  for (auto& b : scene.boundary) resolve_motion_ramp(b.motion, last);
  for (auto& o : scene.obstacles) resolve_motion_ramp(o.motion, last);
  scene.gravity_amplitude.resolve_ramp(last);
  for (auto& p : scene.point_loads) p.amplitude.resolve_ramp(last);
  for (auto& t : scene.tractions) t.amplitude.resolve_ramp(last);
}

}  // namespace sinew
