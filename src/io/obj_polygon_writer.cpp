#include "sinew/io/obj_polygon_writer.hpp"

#include <fmt/format.h>
#include <map>
#include <ostream>
#include <sstream>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/io/text_scanner.hpp"

namespace sinew {

void write_obj_polygon_surface(const std::filesystem::path& path, const PolygonSurface& surface,
                               const Eigen::MatrixX3d& positions, const ObjWriteOptions& options) {
  surface.validate(path.string());
  if (positions.rows() != surface.positions.rows())
    throw Error(fmt::format("{} positions given for a surface of {} vertices", positions.rows(), surface.positions.rows()),
                path.string());
  if (!positions.allFinite()) throw Error("a deformed position is not finite", path.string());

  // Recomputed normals: one per (position, input normal) pair.
  const bool normals = options.normals == ObjNormals::Recompute && surface.normals.rows() > 0;
  std::vector<int> corner_normal(surface.corners.size(), -1);
  std::vector<Eigen::Vector3d> new_normals;
  if (normals) {
    const Eigen::MatrixX3d face_n = surface.face_normals(positions);
    std::map<std::pair<int, int>, int> pair_index;
    for (Eigen::Index f = 0; f < surface.num_faces(); ++f)
      for (int c = surface.face_start[f]; c < surface.face_start[f + 1]; ++c) {
        const auto& corner = surface.corners[c];
        if (corner.normal < 0) continue;
        const auto [it, added] = pair_index.emplace(std::pair{corner.position, corner.normal}, int(new_normals.size()));
        if (added) new_normals.emplace_back(Eigen::Vector3d::Zero());
        new_normals[it->second] += face_n.row(f).transpose();
        corner_normal[c] = it->second;
      }
    for (auto& n : new_normals) {
      const double length = n.norm();
      n = length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::UnitZ();  // degenerate fan: any unit
    }
  }

  write_file_atomically(path, [&](std::ostream& os) {
    fmt::memory_buffer text;
    auto out = std::back_inserter(text);
    fmt::format_to(out, "# written by Sinew: {} vertices, {} faces\n", positions.rows(), surface.num_faces());
    for (const auto& lib : surface.material_libraries) fmt::format_to(out, "mtllib {}\n", lib);
    for (Eigen::Index v = 0; v < positions.rows(); ++v)
      fmt::format_to(out, "v {} {} {}\n", positions(v, 0), positions(v, 1), positions(v, 2));
    for (Eigen::Index t = 0; t < surface.uvs.rows(); ++t) fmt::format_to(out, "vt {} {}\n", surface.uvs(t, 0), surface.uvs(t, 1));
    for (const auto& n : new_normals) fmt::format_to(out, "vn {} {} {}\n", n(0), n(1), n(2));
    int group = -1, object = -1, material = -1, smoothing = -1;
    for (Eigen::Index f = 0; f < surface.num_faces(); ++f) {
      // State statements only where they change, in the order an OBJ reader applies them.
      if (options.objects && surface.face_object[f] != object && surface.face_object[f] >= 0)
        fmt::format_to(out, "o {}\n", surface.objects[surface.face_object[f]]);
      object = surface.face_object[f];
      if (surface.face_group[f] != group) {
        if (surface.face_group[f] >= 0)
          fmt::format_to(out, "g {}\n", surface.groups[surface.face_group[f]]);
        else
          fmt::format_to(out, "g\n");  // back to the default group
      }
      group = surface.face_group[f];
      if (surface.face_material[f] != material && surface.face_material[f] >= 0)
        fmt::format_to(out, "usemtl {}\n", surface.materials[surface.face_material[f]]);
      material = surface.face_material[f];
      if (surface.face_smoothing[f] != smoothing) {
        if (surface.face_smoothing[f] > 0)
          fmt::format_to(out, "s {}\n", surface.face_smoothing[f]);
        else
          fmt::format_to(out, "s off\n");
      }
      smoothing = surface.face_smoothing[f];
      fmt::format_to(out, "f");
      for (int c = surface.face_start[f]; c < surface.face_start[f + 1]; ++c) {
        const auto& corner = surface.corners[c];
        const int n = normals ? corner_normal[c] : -1;
        fmt::format_to(out, " {}", corner.position + 1);
        if (corner.uv >= 0 && n >= 0)
          fmt::format_to(out, "/{}/{}", corner.uv + 1, n + 1);
        else if (corner.uv >= 0)
          fmt::format_to(out, "/{}", corner.uv + 1);
        else if (n >= 0)
          fmt::format_to(out, "//{}", n + 1);
      }
      fmt::format_to(out, "\n");
    }
    os.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

void copy_material_libraries(const PolygonSurface& surface, const std::filesystem::path& source_obj,
                             const std::filesystem::path& out_dir) {
  const std::filesystem::path folder = std::filesystem::absolute(source_obj).parent_path();
  for (const auto& lib : surface.material_libraries) {
    const std::filesystem::path relative(lib);
    if (relative.is_absolute() || relative.lexically_normal().string().starts_with(".."))
      throw Error(fmt::format("material library '{}' must be a path inside the OBJ's folder to be copied beside the output", lib),
                  source_obj.string());
    const std::filesystem::path source = folder / relative;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(source, ec))
      throw Error(fmt::format("material library '{}' not found (looked for {})", lib, source.string()), source_obj.string());
    const std::string text = read_text_file(source);
    // Texture statements end in a file name; relative ones are made absolute.
    std::istringstream in(text);
    std::string copy, line;
    while (std::getline(in, line)) {
      std::string trimmed = line;
      if (!trimmed.empty() && trimmed.back() == '\r') trimmed.pop_back();
      const size_t start = trimmed.find_first_not_of(" \t");
      const std::string key = start == std::string::npos ? "" : trimmed.substr(start, trimmed.find_first_of(" \t", start) - start);
      const bool texture = key.starts_with("map_") || key == "bump" || key == "disp" || key == "decal" || key == "refl" || key == "norm";
      const size_t last = trimmed.find_last_of(" \t");
      if (texture && last != std::string::npos && last + 1 < trimmed.size()) {
        const std::filesystem::path map(trimmed.substr(last + 1));
        if (map.is_relative()) trimmed = trimmed.substr(0, last + 1) + (source.parent_path() / map).lexically_normal().string();
      }
      copy += trimmed + "\n";
    }
    const std::filesystem::path target = out_dir / relative;
    if (target.has_parent_path()) ensure_directory(target.parent_path());
    write_file_atomically(target, [&](std::ostream& os) { os << copy; });
  }
}

}  // namespace sinew
