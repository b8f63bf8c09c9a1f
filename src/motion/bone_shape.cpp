#include "sinew/motion/bone_shape.hpp"

#include <algorithm>
#include <cmath>

#include "sinew/core/error.hpp"
#include "sinew/io/surface_reader.hpp"

namespace sinew {

CapsuleShape::CapsuleShape(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius)
    : a_(a), b_(b), radius_(radius) {
  if (!a.allFinite() || !b.allFinite()) throw Error("capsule end points must be finite", "capsule");
  if (!(std::isfinite(radius) && radius > 0.0)) throw Error("capsule radius must be positive", "capsule");
}

double CapsuleShape::distance_to_axis(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d ab = b_ - a_;
  const double len2 = ab.squaredNorm();
  // A zero-length capsule is a sphere about a.
  const double t = len2 > 0.0 ? std::clamp((p - a_).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a_ + t * ab)).norm();
}

bool CapsuleShape::contains(const Eigen::Vector3d& p) const { return distance_to_axis(p) <= radius_; }

static TriangleSurface validated(TriangleSurface surface, const std::string& source) {
  surface.validate(source, /*require_closed=*/true);
  return surface;
}

MeshBoneShape::MeshBoneShape(TriangleSurface surface, const std::string& source)
    : surface_(validated(std::move(surface), source)), inside_(surface_) {}

bool MeshBoneShape::contains(const Eigen::Vector3d& p) const { return inside_.inside(p); }

std::shared_ptr<MeshBoneShape> load_mesh_bone(const std::filesystem::path& file) {
  return std::make_shared<MeshBoneShape>(read_triangle_surface(file, /*require_closed=*/true), file.string());
}

}  // namespace sinew
