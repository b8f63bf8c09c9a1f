// Obstacle surfaces for output and display (obstacle.hpp: ObstacleShape::surface_mesh,
// Obstacle::surface_at), tessellated by mesh/shape_mesh.hpp.
#include <algorithm>

#include "sinew/mesh/shape_mesh.hpp"
#include "sinew/motion/obstacle.hpp"

namespace sinew {

TriangleSurface PlaneObstacle::surface_mesh(const Eigen::AlignedBox3d& focus) const {
  const Eigen::Vector3d c = focus.isEmpty() ? point_ : focus.center();
  const Eigen::Vector3d on_plane = c - normal_.dot(c - point_) * normal_;
  const double size = focus.isEmpty() ? 1.0 : focus.sizes().maxCoeff();
  return square_mesh(on_plane, normal_, 1.5 * std::max(size, 1e-3));
}
TriangleSurface SphereObstacle::surface_mesh(const Eigen::AlignedBox3d&) const { return sphere_mesh(center_, radius_); }
TriangleSurface CapsuleObstacle::surface_mesh(const Eigen::AlignedBox3d&) const { return capsule_mesh(a_, b_, radius_); }
TriangleSurface CylinderObstacle::surface_mesh(const Eigen::AlignedBox3d&) const {
  return cylinder_mesh(center_, axis_, radius_, 2.0 * half_length_);
}
TriangleSurface BoxObstacle::surface_mesh(const Eigen::AlignedBox3d&) const {
  return box_mesh(center_ - half_, center_ + half_);
}

TriangleSurface Obstacle::surface_at(double frame, const Eigen::AlignedBox3d& focus) const {
  TriangleSurface s = shape_->surface_mesh(focus);
  const RigidTransform T = pose(frame);
  for (Eigen::Index v = 0; v < s.vertices.rows(); ++v) s.vertices.row(v) = T.apply(s.vertices.row(v).transpose()).transpose();
  return s;
}

}  // namespace sinew
