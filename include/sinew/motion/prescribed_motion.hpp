#pragma once
// Kinematic (Dirichlet) boundary conditions: selected vertices follow a rigid motion of the
// frame number (pinned, steady translation, steady rotation about an axis, or keyframes).
#include <Eigen/Geometry>
#include <string>
#include <variant>
#include <vector>

#include "sinew/core/types.hpp"

namespace sinew {

struct RigidTransform {
  Mat3 R = Mat3::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return R * p + t; }
};

struct Pinned {};
struct Translation {
  Eigen::Vector3d per_frame = Eigen::Vector3d::Zero();  // displacement added each frame
};
struct Rotation {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double angle_per_frame = 0.0;  // radians
};
struct Keyframe {
  double frame = 0.0;
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};
struct Keyframes {
  std::vector<Keyframe> keys;  // sorted by frame; slerp/lerp between, held outside the range
};
using RigidMotion = std::variant<Pinned, Translation, Rotation, Keyframes>;

// Transform at (possibly fractional) frame `frame` relative to the rest pose.
RigidTransform transform_at(const RigidMotion& motion, double frame);

// Validates a motion (finite values, non-zero axis, keyframes sorted and non-empty).
void validate_motion(const RigidMotion& motion, const std::string& context);

struct KinematicCondition {
  std::vector<int> vertices;
  RigidMotion motion;
};

// Sets x at every constrained vertex to the motion applied to its rest position and marks
// its DOFs fixed.
void apply_kinematics(const std::vector<KinematicCondition>& conditions, const Eigen::MatrixX3d& rest,
                      double frame, Eigen::VectorXd& x, std::vector<char>& fixed);

}  // namespace sinew
