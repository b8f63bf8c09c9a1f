#pragma once
// Kinematic (Dirichlet) boundary conditions: selected vertices follow a rigid motion of the
// frame number (pinned, steady translation, steady rotation about an axis, keyframes, or a
// displacement scaled by an amplitude), in all three coordinates, in some of them (rollers,
// symmetry planes), or only along one direction (a roller on an inclined plane).
#include <array>
#include <optional>
#include <Eigen/Geometry>
#include <string>
#include <variant>
#include <vector>

#include "sinew/core/types.hpp"
#include "sinew/motion/amplitude.hpp"

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
// Load control for a prescribed displacement: p + amplitude(k) * value.
struct Displacement {
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  Amplitude amplitude;
};
using RigidMotion = std::variant<Pinned, Translation, Rotation, Keyframes, Displacement>;

// Transform at (possibly fractional) frame `frame` relative to the rest pose.
RigidTransform transform_at(const RigidMotion& motion, double frame);

// Validates a motion (finite values, non-zero axis, keyframes sorted and non-empty).
void validate_motion(const RigidMotion& motion, const std::string& context);

struct KinematicCondition {
  std::vector<int> vertices;
  RigidMotion motion;
  std::string source;  // where the motion was given ("scene.json: /boundary/0/motion"), for errors
  // Which coordinates are prescribed (all three by default). Ignored when `direction` is set.
  std::array<bool, 3> components{true, true, true};
  // A unit vector n: only n . x is prescribed (the vertex slides freely across n). Its DOFs are
  // then expressed in a rotated vertex frame whose first axes are its prescribed directions
  // (model/model.cpp); the problem rotates gradients and Hessians to match
  // (assembly/problem.hpp). Axis-aligned directions are better given as `components`.
  std::optional<Eigen::Vector3d> direction;
};

// The orthonormal frame [n, t1, t2] of a direction condition (columns).
Mat3 vertex_frame(const Eigen::Vector3d& n);

// Sets the prescribed coordinates of every constrained vertex to those of the motion applied to
// its rest position and marks those DOFs fixed. A direction condition moves the vertex along n
// only, keeping its tangential position, and leaves the fixed flag to the caller (it marks a DOF
// of the vertex's rotated frame). Projections along orthogonal directions commute, so the order
// of the conditions does not matter. A motion that carries a vertex out of the finite doubles (a translation of
// 1e300 per frame, run long enough) is a sinew::Error naming the condition's source, the frame
// and the vertex, rather than a NaN that fails somewhere later without saying why.
void apply_kinematics(const std::vector<KinematicCondition>& conditions, const Eigen::MatrixX3d& rest,
                      double frame, Eigen::VectorXd& x, std::vector<char>& fixed);

}  // namespace sinew
