#include "sinew/rig/bone_surface.hpp"

#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/mesh/shape_surfaces.hpp"

namespace sinew {

TriangleSurface bone_surface_at(const Bone& bone, double frame) {
  TriangleSurface s;
  if (const auto* capsule = dynamic_cast<const CapsuleShape*>(bone.shape.get()))
    s = capsule_surface(capsule->a(), capsule->b(), capsule->radius());
  else if (const auto* mesh = dynamic_cast<const MeshBoneShape*>(bone.shape.get()))
    s = mesh->surface();
  else
    throw Error(fmt::format("bone shape '{}' has no surface to write", bone.shape ? bone.shape->kind() : "none"), bone.name);
  const Affine34 A = bone.transform_at(frame);
  for (Eigen::Index v = 0; v < s.vertices.rows(); ++v) s.vertices.row(v) = apply(A, s.vertices.row(v).transpose()).transpose();
  return s;
}

}  // namespace sinew
