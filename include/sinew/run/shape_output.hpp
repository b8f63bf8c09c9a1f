#pragma once
// The scene's obstacles and bones written per output frame next to the body, so contact and
// binding can be checked by eye: obstacle_<name>_NNNN.vtu/.obj and bone_<name>_NNNN.vtu/.obj
// (names made file-safe), VTU when the scene writes VTU, OBJ when it writes OBJ. A plane is a
// square under the body, three body sizes wide (ObstacleShape::surface_mesh). A shape that has
// not moved since the previous output frame (a fixed ground, a bone at rest) is not written
// again: its files get the frame's names as hard links to the previous frame's (same bytes,
// nothing to write or sync; io/atomic_file.hpp), or are written where links cannot be made.
#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
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
  void write(const std::filesystem::path& out, int frame);
  // File stems (before _NNNN), in scene order: obstacles, then bones.
  const std::vector<std::string>& stems() const { return stems_; }

 private:
  std::vector<Obstacle> obstacles_;
  std::vector<const Bone*> bones_;
  std::shared_ptr<const Rig> rig_;  // keeps bones_ alive
  std::vector<std::string> stems_;
  Eigen::AlignedBox3d focus_;  // the body's rest bounds
  bool vtu_ = true, obj_ = true;
  // Per shape, the surface of the last frame written and that frame's files.
  struct Written {
    TriangleSurface surface;
    std::filesystem::path vtu, obj;
  };
  std::vector<std::optional<Written>> written_;
};

// "obstacle_" or "bone_" + the name with characters other than letters, digits, '-' and '_'
// replaced by '_'; a name used twice after that gets its index appended.
std::vector<std::string> shape_file_stems(const std::string& prefix, const std::vector<std::string>& names);

}  // namespace sinew
