#pragma once
// The scene's obstacles and bones written per output frame next to the body, so contact and
// binding can be checked by eye: obstacle_<name>_NNNN.vtu/.obj and bone_<name>_NNNN.vtu/.obj
// (names made file-safe), VTU when the scene writes VTU, OBJ when it writes OBJ. A plane is a
// square under the body, three body sizes wide (ObstacleShape::surface_mesh).
#include <Eigen/Geometry>
#include <filesystem>
#include <string>
#include <vector>

#include "sinew/motion/obstacle.hpp"
#include "sinew/mesh/volume_mesh.hpp"
#include "sinew/motion/rig.hpp"
#include "sinew/model/scene.hpp"

namespace sinew {

class ShapeOutput {
 public:
  ShapeOutput(const Scene& scene, const VolumeMesh& mesh);
  bool active() const { return !obstacles_.empty() || !bones_.empty(); }
  void write(const std::filesystem::path& out, int frame) const;
  // File stems (before _NNNN), in scene order: obstacles, then bones.
  const std::vector<std::string>& stems() const { return stems_; }

 private:
  std::vector<Obstacle> obstacles_;
  std::vector<const Bone*> bones_;
  std::shared_ptr<const Rig> rig_;  // keeps bones_ alive
  std::vector<std::string> stems_;
  Eigen::AlignedBox3d focus_;  // the body's rest bounds
  bool vtu_ = true, obj_ = true;
};

// "obstacle_" or "bone_" + the name with characters other than letters, digits, '-' and '_'
// replaced by '_'; a name used twice after that gets its index appended.
std::vector<std::string> shape_file_stems(const std::string& prefix, const std::vector<std::string>& names);

}  // namespace sinew
