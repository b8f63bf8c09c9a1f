#pragma once
// The rest-pose volume of a bone. Lattice vertices inside it at rest are bound to the bone.
// Only the inside test is needed, so a closed triangle mesh can implement it too.
// TODO(lead, after merging helper C): add a MeshBoneShape that wraps the robust inside test
// of include/sinew/mesh/inside_test.hpp over a closed surface read by C's surface readers,
// and let rig_reader.cpp accept {"mesh": "bone.obj"} shapes (it rejects them today).
#include <Eigen/Core>
#include <memory>
#include <string>

namespace sinew {

class BoneShape {
 public:
  virtual ~BoneShape() = default;
  virtual std::string kind() const = 0;
  // True where the rest-space point p lies inside (or on) the bone.
  virtual bool contains(const Eigen::Vector3d& p) const = 0;
};

// All points within `radius` of the segment a-b.
class CapsuleShape final : public BoneShape {
 public:
  CapsuleShape(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius);
  std::string kind() const override { return "capsule"; }
  bool contains(const Eigen::Vector3d& p) const override;
  double distance_to_axis(const Eigen::Vector3d& p) const;  // to the segment a-b
  const Eigen::Vector3d& a() const { return a_; }
  const Eigen::Vector3d& b() const { return b_; }
  double radius() const { return radius_; }

 private:
  Eigen::Vector3d a_, b_;
  double radius_;
};

}  // namespace sinew
