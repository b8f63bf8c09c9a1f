// Obstacle surfaces for output (obstacle.hpp: ObstacleShape::surface_mesh, Obstacle::surface_at).
#include "sinew/contact/obstacle.hpp"
#include "sinew/mesh/shape_surfaces.hpp"

namespace sinew {

TriangleSurface PlaneObstacle::surface_mesh(double half_extent) const {
  return square_surface(point_, normal_, half_extent);
}
TriangleSurface SphereObstacle::surface_mesh(double) const { return sphere_surface(center_, radius_); }
TriangleSurface CapsuleObstacle::surface_mesh(double) const { return capsule_surface(a_, b_, radius_); }
TriangleSurface CylinderObstacle::surface_mesh(double) const {
  return cylinder_surface(center_, axis_, radius_, 2.0 * half_length_);
}
TriangleSurface BoxObstacle::surface_mesh(double) const { return box_surface(center_ - half_, center_ + half_); }

TriangleSurface Obstacle::surface_at(double frame, double half_extent) const {
  TriangleSurface s = shape_->surface_mesh(half_extent);
  const RigidTransform T = pose(frame);
  for (Eigen::Index v = 0; v < s.vertices.rows(); ++v)
    s.vertices.row(v) = T.apply(s.vertices.row(v).transpose()).transpose();
  return s;
}

}  // namespace sinew
