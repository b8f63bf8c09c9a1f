#pragma once
// Rigid obstacles for contact: a shape given in its rest pose (plane, sphere, capsule, finite
// capped cylinder, box) moved by a rigid path of the frame number (static, steady translation or
// rotation, or keyframes with lerp/slerp, the same motions as kinematic boundary conditions).
// Contact models only need signed distance, closest point, outward normal and its derivative,
// and how an obstacle-attached point moves between two times.
#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "sinew/core/types.hpp"
#include "sinew/motion/prescribed_motion.hpp"
#include "sinew/mesh/triangle_surface.hpp"

namespace sinew {

// Where a point lies relative to a shape.
struct SurfaceQuery {
  double distance = 0.0;                       // signed: negative inside
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // outward unit normal = gradient of distance
  Eigen::Vector3d closest = Eigen::Vector3d::Zero();  // nearest surface point (p - distance * normal)
  // d(normal)/dp: the Hessian of the signed distance. Exact inside the shape (the only region
  // a penetration energy sees); outside it is left zero.
  Mat3 normal_derivative = Mat3::Zero();
};

class ObstacleShape {
 public:
  virtual ~ObstacleShape() = default;
  virtual std::string type() const = 0;
  virtual SurfaceQuery query(const Eigen::Vector3d& p) const = 0;  // in the rest pose
  // Its surface in the rest pose as closed outward triangles, for output and display
  // (motion/obstacle_surface.cpp). `focus` is the body's rest bounds: the unbounded plane is
  // shown as a square centred under it, three body sizes wide; bounded shapes ignore it.
  virtual TriangleSurface surface_mesh(const Eigen::AlignedBox3d& focus) const = 0;
};

// Half-space below the plane through `point` with outward `normal` (the ground: normal up).
class PlaneObstacle final : public ObstacleShape {
 public:
  PlaneObstacle(const Eigen::Vector3d& point, const Eigen::Vector3d& normal);
  std::string type() const override { return "plane"; }
  SurfaceQuery query(const Eigen::Vector3d& p) const override;
  const Eigen::Vector3d& point() const { return point_; }
  const Eigen::Vector3d& normal() const { return normal_; }
  TriangleSurface surface_mesh(const Eigen::AlignedBox3d& focus) const override;

 private:
  Eigen::Vector3d point_, normal_;
};

class SphereObstacle final : public ObstacleShape {
 public:
  SphereObstacle(const Eigen::Vector3d& center, double radius);
  std::string type() const override { return "sphere"; }
  SurfaceQuery query(const Eigen::Vector3d& p) const override;
  const Eigen::Vector3d& center() const { return center_; }
  double radius() const { return radius_; }
  TriangleSurface surface_mesh(const Eigen::AlignedBox3d& focus) const override;

 private:
  Eigen::Vector3d center_;
  double radius_;
};

// All points within `radius` of the segment [a, b].
class CapsuleObstacle final : public ObstacleShape {
 public:
  CapsuleObstacle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius);
  std::string type() const override { return "capsule"; }
  SurfaceQuery query(const Eigen::Vector3d& p) const override;
  const Eigen::Vector3d& a() const { return a_; }
  const Eigen::Vector3d& b() const { return b_; }
  double radius() const { return radius_; }
  TriangleSurface surface_mesh(const Eigen::AlignedBox3d& focus) const override;

 private:
  Eigen::Vector3d a_, b_;
  double radius_;
};

// Finite cylinder with flat caps: axis through `center` along `axis`, total length `length`.
class CylinderObstacle final : public ObstacleShape {
 public:
  CylinderObstacle(const Eigen::Vector3d& center, const Eigen::Vector3d& axis, double radius, double length);
  std::string type() const override { return "cylinder"; }
  SurfaceQuery query(const Eigen::Vector3d& p) const override;
  const Eigen::Vector3d& center() const { return center_; }
  const Eigen::Vector3d& axis() const { return axis_; }  // unit
  double radius() const { return radius_; }
  double length() const { return 2.0 * half_length_; }
  TriangleSurface surface_mesh(const Eigen::AlignedBox3d& focus) const override;

 private:
  Eigen::Vector3d center_, axis_;
  double radius_, half_length_;
};

// Axis-aligned (in the rest pose) box [lo, hi]; a path may rotate it.
class BoxObstacle final : public ObstacleShape {
 public:
  BoxObstacle(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
  std::string type() const override { return "box"; }
  SurfaceQuery query(const Eigen::Vector3d& p) const override;
  Eigen::Vector3d lo() const { return center_ - half_; }
  Eigen::Vector3d hi() const { return center_ + half_; }
  TriangleSurface surface_mesh(const Eigen::AlignedBox3d& focus) const override;

 private:
  Eigen::Vector3d center_, half_;
};

class Obstacle {
 public:
  Obstacle(std::string name, std::shared_ptr<const ObstacleShape> shape, RigidMotion path = Pinned{});

  const std::string& name() const { return name_; }
  const ObstacleShape& shape() const { return *shape_; }
  const RigidMotion& path() const { return path_; }
  bool moves() const;

  // Throws a sinew::Error naming the obstacle and frame when the path has left the finite numbers.
  RigidTransform pose(double frame) const;
  // The shape's surface moved to `frame` (see ObstacleShape::surface_mesh).
  TriangleSurface surface_at(double frame, const Eigen::AlignedBox3d& focus) const;
  // The query of a world-space point against the obstacle at `frame`, in world space.
  SurfaceQuery query(const Eigen::Vector3d& p, double frame) const;
  // How far the obstacle material point at p (world, at frame0) moves by frame1.
  Eigen::Vector3d displacement(const Eigen::Vector3d& p, double frame0, double frame1) const;
  // Velocity of the obstacle material point at p (world, at `frame`), frames lasting
  // `seconds_per_frame`: the forward difference of the path over 1e-6 frame (one-sided, so
  // the motion after a keyframe counts), exact to ~1e-6 relative for rotations.
  Eigen::Vector3d velocity(const Eigen::Vector3d& p, double frame, double seconds_per_frame) const;

 private:
  std::string name_;
  std::shared_ptr<const ObstacleShape> shape_;
  RigidMotion path_;
};

}  // namespace sinew
