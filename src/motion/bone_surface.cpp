#include "sinew/motion/bone_surface.hpp"

#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/mesh/shape_mesh.hpp"

namespace sinew {

TriangleSurface bone_rest_surface(const BoneShape& shape) {
  if (const auto* capsule = dynamic_cast<const CapsuleShape*>(&shape))
    return capsule_mesh(capsule->a(), capsule->b(), capsule->radius(), 16);
  if (const auto* mesh = dynamic_cast<const MeshBoneShape*>(&shape)) return mesh->surface();
  throw Error(fmt::format("bone shape '{}' has no surface to write", shape.kind()), "bone");
}

TriangleSurface bone_surface_at(const Bone& bone, double frame) {
  if (!bone.shape) throw Error("bone has no shape to write", bone.name);
  TriangleSurface s;
  try {
    s = bone_rest_surface(*bone.shape);
  } catch (const Error& e) {
    throw e.within(bone.name);
  }
  const Affine34 A = bone.transform_at(frame);
  for (Eigen::Index v = 0; v < s.vertices.rows(); ++v) s.vertices.row(v) = apply(A, s.vertices.row(v).transpose()).transpose();
  return s;
}

}  // namespace sinew
