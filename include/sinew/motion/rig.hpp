#pragma once
// A rig: bones (a rest shape plus keyframed transforms over frames) that drive the flesh
// lattice kinematically (paper 000 §6, Torso and Hand). Production skinning rigs give noisy,
// non-rigid and intersecting bone transforms; nothing here requires them to be clean.
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "sinew/motion/bone_shape.hpp"

namespace sinew {

using Affine34 = Eigen::Matrix<double, 3, 4>;  // x = A.leftCols<3>() X + A.col(3)

// A bone transform at one (possibly fractional) frame, relative to the rest pose.
struct BoneKey {
  double frame = 0.0;
  // Rigid keys: x = R (X - c) + c + t with R = rotation, c = center (the pivot), t =
  // translation. Affine keys: `affine` only.
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Affine34 affine = Affine34::Identity();
};

enum class BoneMotion {
  Rigid,   // keys interpolated by slerp (rotation) and lerp (translation, pivot): a turn about a
           // fixed pivot keeps the pivot in place between keys
  Affine,  // keys interpolated component-wise; shears and scalings allowed
};

struct Bone {
  std::string name;
  std::shared_ptr<const BoneShape> shape;
  BoneMotion motion = BoneMotion::Rigid;
  std::vector<BoneKey> keys;  // sorted by frame, at least one; held constant outside the range

  // The rest-to-frame map at `frame`.
  Affine34 transform_at(double frame) const;
};

enum class BoneBinding {
  Hard,     // bound vertices are Dirichlet DOFs that follow their bone exactly
  Springs,  // bound vertices are pulled to their bone's target by stiff springs
};

struct Rig {
  std::vector<Bone> bones;
  BoneBinding binding = BoneBinding::Hard;
  double spring_stiffness = 0.0;  // N/m per bound vertex (Springs only)
};

// Applies x = A.leftCols<3>() X + A.col(3).
inline Eigen::Vector3d apply(const Affine34& A, const Eigen::Vector3d& X) {
  return A.leftCols<3>() * X + A.col(3);
}

// Checks names, finite keys, unit-able quaternions, sorted frames; throws sinew::Error in `context`.
void validate_rig(const Rig& rig, const std::string& context);

// Which bone each vertex follows: bone[v] = index into rig.bones, or -1 for free flesh.
// A vertex inside several (intersecting) bones follows the first of them in rig order, so the
// binding is deterministic and every vertex has at most one target.
struct RigBinding {
  std::vector<int> bone;
  std::vector<int> bound_vertices;  // sorted
  std::vector<int> count_per_bone;
};
RigBinding bind_rig(const Rig& rig, const Eigen::MatrixX3d& rest);

// Target position of every bound vertex at `frame` (3 entries per vertex; free ones hold rest).
Eigen::VectorXd rig_targets(const Rig& rig, const RigBinding& binding, const Eigen::MatrixX3d& rest,
                            double frame);

// Hard binding: sets x at every bound vertex to its target and marks its DOFs fixed.
void apply_rig(const Rig& rig, const RigBinding& binding, const Eigen::MatrixX3d& rest, double frame,
               Eigen::VectorXd& x, std::vector<char>& fixed);

}  // namespace sinew
