#include "sinew/run/shape_output.hpp"

#include <fmt/format.h>
#include <cctype>
#include <set>

#include "sinew/io/obj_writer.hpp"
#include "sinew/io/vtk_writer.hpp"
#include "sinew/motion/bone_surface.hpp"

namespace sinew {

std::vector<std::string> shape_file_stems(const std::string& prefix, const std::vector<std::string>& names) {
  std::vector<std::string> stems;
  std::set<std::string> seen;
  for (size_t i = 0; i < names.size(); ++i) {
    std::string safe = names[i].empty() ? std::to_string(i) : names[i];
    for (char& c : safe)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    std::string stem = prefix + safe;
    if (!seen.insert(stem).second) {
      stem += fmt::format("_{}", i);
      seen.insert(stem);
    }
    stems.push_back(stem);
  }
  return stems;
}

ShapeOutput::ShapeOutput(const Scene& scene, const VolumeMesh& mesh) : vtu_(scene.output.vtu), obj_(scene.output.obj) {
  std::vector<std::string> obstacle_names, bone_names;
  for (const ObstacleSpec& o : scene.obstacles) {
    obstacles_.emplace_back(o.name, o.shape, o.motion);
    obstacle_names.push_back(o.name);
  }
  if (scene.rig) {
    rig_ = scene.rig;
    for (const Bone& b : rig_->bones) {
      bones_.push_back(&b);
      bone_names.push_back(b.name);
    }
  }
  stems_ = shape_file_stems("obstacle_", obstacle_names);
  const auto bone_stems = shape_file_stems("bone_", bone_names);
  stems_.insert(stems_.end(), bone_stems.begin(), bone_stems.end());
  for (Eigen::Index v = 0; v < mesh.num_vertices(); ++v) focus_.extend(mesh.vertices.row(v).transpose());
}

void ShapeOutput::write(const std::filesystem::path& out, int frame) const {
  auto write_one = [&](const std::string& stem, const TriangleSurface& s) {
    if (vtu_) write_surface_vtu(out / fmt::format("{}_{:04d}.vtu", stem, frame), s);
    if (obj_) write_obj(out / fmt::format("{}_{:04d}.obj", stem, frame), s.vertices, s.faces);
  };
  size_t k = 0;
  for (const Obstacle& o : obstacles_) write_one(stems_[k++], o.surface_at(frame, focus_));
  for (const Bone* b : bones_) write_one(stems_[k++], bone_surface_at(*b, frame));
}

}  // namespace sinew
