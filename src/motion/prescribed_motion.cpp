#include "sinew/motion/prescribed_motion.hpp"

#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

RigidTransform transform_at(const RigidMotion& motion, double frame) {
  RigidTransform T;
  if (const auto* tr = std::get_if<Translation>(&motion)) {
    T.t = frame * tr->per_frame;
  } else if (const auto* rot = std::get_if<Rotation>(&motion)) {
    T.R = Eigen::AngleAxisd(frame * rot->angle_per_frame, rot->axis.normalized()).toRotationMatrix();
    T.t = rot->center - T.R * rot->center;
  } else if (const auto* kf = std::get_if<Keyframes>(&motion)) {
    const auto& k = kf->keys;
    if (frame <= k.front().frame) {
      T.R = k.front().rotation.toRotationMatrix();
      T.t = k.front().translation;
    } else if (frame >= k.back().frame) {
      T.R = k.back().rotation.toRotationMatrix();
      T.t = k.back().translation;
    } else {
      size_t i = 1;
      while (k[i].frame < frame) ++i;
      const double s = (frame - k[i - 1].frame) / (k[i].frame - k[i - 1].frame);
      T.R = k[i - 1].rotation.slerp(s, k[i].rotation).toRotationMatrix();
      T.t = (1.0 - s) * k[i - 1].translation + s * k[i].translation;
    }
  }
  return T;
}

void validate_motion(const RigidMotion& motion, const std::string& context) {
  if (const auto* tr = std::get_if<Translation>(&motion)) {
    if (!tr->per_frame.allFinite()) throw Error("translation has a non-finite component", context);
  } else if (const auto* rot = std::get_if<Rotation>(&motion)) {
    if (!rot->center.allFinite() || !rot->axis.allFinite() || !std::isfinite(rot->angle_per_frame))
      throw Error("rotation has a non-finite value", context);
    if (!(rot->axis.norm() > 0.0)) throw Error("rotation axis must be non-zero", context);
  } else if (const auto* kf = std::get_if<Keyframes>(&motion)) {
    if (kf->keys.empty()) throw Error("keyframes list is empty", context);
    for (size_t i = 0; i < kf->keys.size(); ++i) {
      const auto& key = kf->keys[i];
      if (!std::isfinite(key.frame) || !key.translation.allFinite() || !key.rotation.coeffs().allFinite())
        throw Error(fmt::format("keyframe {} has a non-finite value", i), context);
      if (i > 0 && !(key.frame > kf->keys[i - 1].frame))
        throw Error(fmt::format("keyframe {} is not after keyframe {} (frames must increase)", i, i - 1), context);
    }
  }
}

void apply_kinematics(const std::vector<KinematicCondition>& conditions, const Eigen::MatrixX3d& rest,
                      double frame, Eigen::VectorXd& x, std::vector<char>& fixed) {
  for (const auto& c : conditions) {
    const RigidTransform T = transform_at(c.motion, frame);
    for (int v : c.vertices) {
      x.segment<3>(3 * v) = T.apply(rest.row(v).transpose());
      fixed[3 * v] = fixed[3 * v + 1] = fixed[3 * v + 2] = 1;
    }
  }
}

}  // namespace sinew
