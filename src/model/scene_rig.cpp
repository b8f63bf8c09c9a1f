#include "sinew/model/scene_rig.hpp"

#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/model/rig_reader.hpp"

namespace sinew {

void parse_scene_rig(JsonObject& root, Scene& scene) {
  if (root.has("rig")) {
    const nlohmann::json& j = root.raw("rig");
    if (j.is_string()) {
      std::filesystem::path path = j.get<std::string>();
      if (path.is_relative()) path = scene.file.parent_path() / path;
      try {
        scene.rig = std::make_shared<Rig>(load_rig(path));
      } catch (const Error& e) {
        throw e.within(root.file() + ": " + root.path_of("rig"));
      }
    } else if (j.is_object()) {
      JsonObject o = root.object("rig");
      scene.rig = std::make_shared<Rig>(parse_rig(o));
    } else {
      root.fail("rig", "must be a rig file path or a rig object");
    }
  }
  if (root.has("self_contact")) {
    JsonObject o = root.object("self_contact");
    o.allow({"stiffness", "samples", "refine", "refine_iterations"});
    auto s = std::make_shared<SelfContactSettings>();
    s->stiffness = o.positive("stiffness");
    o.choice("samples", {"vertices"}, "vertices");  // boundary vertices are the surface samples
    s->refine = o.boolean("refine", false);
    s->refine_iterations = o.integer("refine_iterations", 0, s->refine_iterations);
    o.finish();
    scene.self_contact = std::move(s);
  }
}

void SceneRig::apply(double frame, const Eigen::MatrixX3d& rest, Eigen::VectorXd& x, std::vector<char>& fixed) const {
  if (!rig) return;
  if (springs) {
    springs->set_frame(frame);
    return;
  }
  apply_rig(*rig, binding, rest, frame, x, fixed);
}

SceneRig make_scene_rig(const Scene& scene, const VolumeMesh& mesh, Problem& problem) {
  SceneRig r;
  if (scene.rig) {
    r.rig = scene.rig;
    r.binding = bind_rig(*r.rig, mesh.vertices);
    for (size_t b = 0; b < r.rig->bones.size(); ++b)
      if (r.binding.count_per_bone[b] == 0)
        throw Error(fmt::format("bone \"{}\" holds no mesh vertex at rest", r.rig->bones[b].name),
                    fmt::format("{}: /rig/bones/{}", scene.file.string(), b));
    if (r.rig->binding == BoneBinding::Springs) {
      r.springs = std::make_shared<BoneSpringForm>(r.rig, r.binding, mesh.vertices, r.rig->spring_stiffness);
      problem.add_form(r.springs);
    }
  }
  if (scene.self_contact) {
    r.contact = std::make_shared<SelfContactForm>(mesh, *scene.self_contact);
    problem.add_form(r.contact);
  }
  return r;
}

}  // namespace sinew
