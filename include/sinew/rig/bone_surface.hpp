#pragma once
// A bone's surface at a frame, for output next to the flesh (capsules tessellated, mesh bones as
// read), moved by the bone's rest-to-frame transform.
#include "sinew/mesh/triangle_surface.hpp"
#include "sinew/rig/rig.hpp"

namespace sinew {

// A sinew::Error names the bone when its shape has no surface (a BoneShape kind added later).
TriangleSurface bone_surface_at(const Bone& bone, double frame);

}  // namespace sinew
