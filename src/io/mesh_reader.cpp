#include "sinew/io/mesh_reader.hpp"

#include <algorithm>
#include <cctype>
#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/element/reorient.hpp"
#include "sinew/element/mesh_validation.hpp"

namespace sinew {

VolumeMesh read_volume_mesh(const std::filesystem::path& path, const MeshReadOptions& options) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  VolumeMesh mesh;
  if (ext == ".mesh") {
    mesh = read_medit_mesh(path);
  } else if (ext == ".vtk") {
    mesh = read_vtk_legacy_mesh(path);
  } else if (ext == ".vtu") {
    mesh = read_vtu_mesh(path);
  } else if (ext == ".msh") {
    mesh = read_gmsh_mesh(path);
  } else if (ext == ".node" || ext == ".ele") {
    mesh = read_tetgen_mesh(path);
  } else if (ext == ".meshb") {
    throw Error("binary MEDIT (.meshb) is not supported; convert it to ASCII .mesh", path.string());
  } else {
    throw Error(fmt::format("unknown mesh file extension '{}'; supported: .mesh (MEDIT ASCII), "
                            ".vtk (legacy VTK ASCII), .vtu (VTK XML UnstructuredGrid), .msh (Gmsh ASCII 2.2/4.1), "
                            ".node/.ele (TetGen)",
                            ext),
                path.string());
  }
  if (options.reorient_inverted) reorient_inverted_elements(mesh);
  validate_mesh(mesh, path.string());
  return mesh;
}

}  // namespace sinew
