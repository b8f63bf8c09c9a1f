#pragma once
// A bone's surface, for output and display next to the flesh: capsules tessellated
// (mesh/shape_mesh.hpp), mesh bones as read; at a frame, moved by the bone's rest-to-frame
// transform.
#include "sinew/mesh/triangle_surface.hpp"
#include "sinew/motion/rig.hpp"

namespace sinew {

// In the rest pose. A sinew::Error names the shape when it has no surface (a kind added later).
TriangleSurface bone_rest_surface(const BoneShape& shape);
// bone_rest_surface moved to `frame`; errors name the bone.
TriangleSurface bone_surface_at(const Bone& bone, double frame);

}  // namespace sinew
