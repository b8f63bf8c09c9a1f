#pragma once
// The scene's "rig" (bones, docs/rig-format.md) and "self_contact" sections: parsing, and the
// pieces run_scene adds to its problem.
#include <memory>

#include "sinew/forms/self_contact_form.hpp"
#include "sinew/forms/bone_spring_form.hpp"
#include "sinew/motion/rig.hpp"
#include "sinew/model/json_reader.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/assembly/problem.hpp"

namespace sinew {

// Reads "rig" (a rig file path relative to the scene's folder, or the rig object inline) and
// "self_contact" ({"stiffness", "samples": "vertices", "refine", "refine_iterations"}).
void parse_scene_rig(JsonObject& root, Scene& scene);

// Bones bound to the scene mesh and, where asked for, the spring and self-contact forms added to
// the problem.
struct SceneRig {
  std::shared_ptr<const Rig> rig;
  RigBinding binding;
  std::shared_ptr<BoneSpringForm> springs;  // soft binding only
  std::shared_ptr<SelfContactForm> contact;

  // Hard binding: bound vertices follow their bones (after the boundary conditions, so a bone
  // wins over a boundary motion on a shared vertex). Soft binding: moves the spring targets.
  void apply(double frame, const Eigen::MatrixX3d& rest, Eigen::VectorXd& x, std::vector<char>& fixed) const;
};
SceneRig make_scene_rig(const Scene& scene, const VolumeMesh& mesh, Problem& problem);

}  // namespace sinew
