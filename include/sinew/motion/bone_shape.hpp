#pragma once
// The rest-pose volume of a bone. Lattice vertices inside it at rest are bound to the bone.
// Only the inside test is needed, so a closed triangle mesh implements it too (MeshBoneShape).
#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <string>

#include "sinew/mesh/inside_test.hpp"

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

// The solid enclosed by a closed triangle surface (a bone mesh exported from a skinning rig).
// Points on the surface count as inside, like the capsule's boundary.
class MeshBoneShape final : public BoneShape {
 public:
  // `surface` must be closed (TriangleSurface::validate); `source` names it in errors.
  MeshBoneShape(TriangleSurface surface, const std::string& source);
  std::string kind() const override { return "mesh"; }
  bool contains(const Eigen::Vector3d& p) const override;
  const TriangleSurface& surface() const { return surface_; }

 private:
  TriangleSurface surface_;
  InsideTest inside_;  // built once over surface_: the AABB tree answers every lattice vertex
};

// Reads a closed bone surface (OBJ, STL, PLY, OFF; io/surface_reader.hpp). An open, inside-out
// or unreadable file is a sinew::Error naming the file.
std::shared_ptr<MeshBoneShape> load_mesh_bone(const std::filesystem::path& file);

}  // namespace sinew
