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
  } else if (const auto* d = std::get_if<Displacement>(&motion)) {
    T.t = d->amplitude.at(frame) * d->value;
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
  if (const auto* d = std::get_if<Displacement>(&motion)) {
    if (!d->value.allFinite()) throw Error("displacement has a non-finite component", context);
    validate_amplitude(d->amplitude, context + "/amplitude");
  } else if (const auto* tr = std::get_if<Translation>(&motion)) {
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

Mat3 vertex_frame(const Eigen::Vector3d& n) {
  const Eigen::Vector3d u = n.normalized();
  // The coordinate axis least aligned with n gives a well-conditioned first tangent.
  Eigen::Index k = 0;
  u.cwiseAbs().minCoeff(&k);
  const Eigen::Vector3d t1 = u.cross(Eigen::Vector3d::Unit(k)).normalized();
  Mat3 Q;
  Q.col(0) = u;
  Q.col(1) = t1;
  Q.col(2) = u.cross(t1);
  return Q;
}

void apply_kinematics(const std::vector<KinematicCondition>& conditions, const Eigen::MatrixX3d& rest,
                      double frame, Eigen::VectorXd& x, std::vector<char>& fixed) {
  for (const auto& c : conditions) {
    const RigidTransform T = transform_at(c.motion, frame);
    for (int v : c.vertices) {
      const Eigen::Vector3d p = T.apply(rest.row(v).transpose());
      if (!p.allFinite())
        throw Error(fmt::format("at frame {:g} the motion moves vertex {} to ({:g}, {:g}, {:g}), out of the finite "
                                "numbers; use a smaller motion or fewer frames",
                                frame, v, p(0), p(1), p(2)),
                    c.source.empty() ? std::string("motion") : c.source);
      if (c.direction) {
        const Eigen::Vector3d& n = *c.direction;
        x.segment<3>(3 * v) += n * n.dot(p - x.segment<3>(3 * v));
        continue;  // its fixed flag is a DOF of the vertex's rotated frame: the caller's to set
      }
      for (int i = 0; i < 3; ++i) {
        if (!c.components[i]) continue;
        x(3 * v + i) = p(i);
        fixed[3 * v + i] = 1;
      }
    }
  }
}

}  // namespace sinew
