#include "sinew/run/shape_output.hpp"

#include <fmt/format.h>
#include <cctype>
#include <set>
#include <utility>

#include "sinew/io/atomic_file.hpp"
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

namespace {

bool same_surface(const TriangleSurface& a, const TriangleSurface& b) {
  return a.vertices.rows() == b.vertices.rows() && a.faces.rows() == b.faces.rows() && a.vertices == b.vertices &&
         a.faces == b.faces;
}

}  // namespace

void ShapeOutput::write(const std::filesystem::path& out, int frame) {
  written_.resize(stems_.size());
  auto write_one = [&](size_t k, TriangleSurface s) {
    std::optional<Written>& last = written_[k];
    const bool unchanged = last && same_surface(last->surface, s);
    Written now{std::move(s), out / fmt::format("{}_{:04d}.vtu", stems_[k], frame),
                out / fmt::format("{}_{:04d}.obj", stems_[k], frame)};
    if (vtu_ && !(unchanged && link_file_atomically(last->vtu, now.vtu))) write_surface_vtu(now.vtu, now.surface);
    if (obj_ && !(unchanged && link_file_atomically(last->obj, now.obj)))
      write_obj(now.obj, now.surface.vertices, now.surface.faces);
    last = std::move(now);
  };
  size_t k = 0;
  for (const Obstacle& o : obstacles_) write_one(k++, o.surface_at(frame, focus_));
  for (const Bone* b : bones_) write_one(k++, bone_surface_at(*b, frame));
}

}  // namespace sinew
