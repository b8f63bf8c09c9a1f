#include "sinew/motion/rig.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <set>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// [R | c + t - R c]: x = R (X - c) + c + t.
Affine34 rigid_matrix(const Eigen::Quaterniond& q, const Eigen::Vector3d& t, const Eigen::Vector3d& c) {
  Affine34 A;
  A.leftCols<3>() = q.normalized().toRotationMatrix();
  A.col(3) = c + t - A.leftCols<3>() * c;
  return A;
}

Affine34 key_matrix(const Bone& bone, const BoneKey& k) {
  return bone.motion == BoneMotion::Rigid ? rigid_matrix(k.rotation, k.translation, k.center) : k.affine;
}

}  // namespace

Affine34 Bone::transform_at(double frame) const {
  if (keys.empty()) throw Error("bone has no keyframe", "bone " + name);
  if (frame <= keys.front().frame) return key_matrix(*this, keys.front());
  if (frame >= keys.back().frame) return key_matrix(*this, keys.back());
  const auto next = std::upper_bound(keys.begin(), keys.end(), frame,
                                     [](double f, const BoneKey& k) { return f < k.frame; });
  const BoneKey& k1 = *next;
  const BoneKey& k0 = *(next - 1);
  const double s = (frame - k0.frame) / (k1.frame - k0.frame);
  if (motion == BoneMotion::Affine) return (1.0 - s) * k0.affine + s * k1.affine;
  // slerp takes the shorter arc (Eigen flips the sign of one quaternion when needed). The pivot
  // is interpolated apart from the translation, so a turn about a fixed pivot stays a turn
  // about it between keys (folding c - R c into t and lerping that would swing the pivot).
  const Eigen::Quaterniond q = k0.rotation.normalized().slerp(s, k1.rotation.normalized());
  return rigid_matrix(q, (1.0 - s) * k0.translation + s * k1.translation, (1.0 - s) * k0.center + s * k1.center);
}

void validate_rig(const Rig& rig, const std::string& context) {
  if (rig.bones.empty()) throw Error("a rig needs at least one bone", context);
  std::set<std::string> names;
  for (size_t b = 0; b < rig.bones.size(); ++b) {
    const Bone& bone = rig.bones[b];
    const std::string where = fmt::format("{}: /bones/{}", context, b);
    if (bone.name.empty()) throw Error("bone name must not be empty", where);
    if (!names.insert(bone.name).second) throw Error(fmt::format("duplicate bone name \"{}\"", bone.name), where);
    if (!bone.shape) throw Error("bone has no shape", where);
    if (bone.keys.empty()) throw Error("bone needs at least one keyframe", where);
    for (size_t k = 0; k < bone.keys.size(); ++k) {
      const BoneKey& key = bone.keys[k];
      const std::string kw = fmt::format("{}/keys/{}", where, k);
      if (!std::isfinite(key.frame)) throw Error("frame must be finite", kw);
      if (k > 0 && !(key.frame > bone.keys[k - 1].frame)) throw Error("keyframes must have increasing frames", kw);
      if (bone.motion == BoneMotion::Rigid) {
        if (!key.rotation.coeffs().allFinite() || !(key.rotation.norm() > 1e-12) || !key.translation.allFinite() ||
            !key.center.allFinite())
          throw Error("rigid key needs a finite non-zero rotation and a finite translation", kw);
      } else if (!key.affine.allFinite()) {
        throw Error("affine key must be finite", kw);
      }
    }
  }
  if (rig.binding == BoneBinding::Springs && !(std::isfinite(rig.spring_stiffness) && rig.spring_stiffness > 0.0))
    throw Error("spring binding needs a positive spring stiffness", context);
}

RigBinding bind_rig(const Rig& rig, const Eigen::MatrixX3d& rest) {
  RigBinding out;
  out.bone.assign(rest.rows(), -1);
  out.count_per_bone.assign(rig.bones.size(), 0);
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    const Eigen::Vector3d X = rest.row(v).transpose();
    for (size_t b = 0; b < rig.bones.size(); ++b) {
      if (rig.bones[b].shape->contains(X)) {
        out.bone[v] = static_cast<int>(b);  // first bone in rig order wins
        ++out.count_per_bone[b];
        out.bound_vertices.push_back(static_cast<int>(v));
        break;
      }
    }
  }
  return out;
}

Eigen::VectorXd rig_targets(const Rig& rig, const RigBinding& binding, const Eigen::MatrixX3d& rest, double frame) {
  std::vector<Affine34> A(rig.bones.size());
  for (size_t b = 0; b < rig.bones.size(); ++b) A[b] = rig.bones[b].transform_at(frame);
  Eigen::VectorXd t(3 * rest.rows());
  for (Eigen::Index v = 0; v < rest.rows(); ++v) {
    const Eigen::Vector3d X = rest.row(v).transpose();
    t.segment<3>(3 * v) = binding.bone[v] < 0 ? X : apply(A[binding.bone[v]], X);
  }
  return t;
}

void apply_rig(const Rig& rig, const RigBinding& binding, const Eigen::MatrixX3d& rest, double frame,
               Eigen::VectorXd& x, std::vector<char>& fixed) {
  const Eigen::VectorXd t = rig_targets(rig, binding, rest, frame);
  for (int v : binding.bound_vertices) {
    x.segment<3>(3 * v) = t.segment<3>(3 * v);
    for (int i = 0; i < 3; ++i) fixed[3 * v + i] = 1;
  }
}

}  // namespace sinew
