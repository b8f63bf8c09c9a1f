#pragma once
// Triangle meshes of the analytic shapes obstacles and bones are made of, for display (the
// browser viewer); contact uses the exact shapes. Every mesh is closed (except the square)
// and counter-clockwise seen from outside.
#include <Eigen/Core>

#include "sinew/mesh/triangle_surface.hpp"

namespace sinew {

// `segments` points around each ring (at least 3); latitude rings scale with it.
TriangleSurface sphere_mesh(const Eigen::Vector3d& center, double radius, int segments = 24);
// All points within `radius` of the segment a-b.
TriangleSurface capsule_mesh(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius, int segments = 24);
// Flat-capped cylinder about `axis` through `center`, total length `length`.
TriangleSurface cylinder_mesh(const Eigen::Vector3d& center, const Eigen::Vector3d& axis, double radius, double length,
                              int segments = 24);
TriangleSurface box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
// A square of side 2 half_size centred at `center` in the plane with unit `normal` (facing it).
TriangleSurface square_mesh(const Eigen::Vector3d& center, const Eigen::Vector3d& normal, double half_size);

}  // namespace sinew
