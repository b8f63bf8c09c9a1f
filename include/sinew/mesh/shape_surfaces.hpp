#pragma once
// Triangle surfaces of the analytic shapes obstacles and bones are made of, for writing them
// out (ParaView, renderers) next to the simulated body. Closed shapes come out closed and
// outward (TriangleSurface::validate passes); the plane is a finite square.
#include <Eigen/Core>

#include "sinew/mesh/triangle_surface.hpp"

namespace sinew {

// `segments` points around the axis; rings along curved parts scale with it.
TriangleSurface sphere_surface(const Eigen::Vector3d& center, double radius, int segments = 24);
// Points within `radius` of the segment a-b (a sphere when a == b).
TriangleSurface capsule_surface(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius, int segments = 24);
// Flat-capped cylinder: axis through `center` along `axis` (any length), total `length`.
TriangleSurface cylinder_surface(const Eigen::Vector3d& center, const Eigen::Vector3d& axis, double radius,
                                 double length, int segments = 24);
TriangleSurface box_surface(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
// A square of side 2 * half_size through `point`, facing along `normal` (two triangles).
TriangleSurface square_surface(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double half_size);

}  // namespace sinew
