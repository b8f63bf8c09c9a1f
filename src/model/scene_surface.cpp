#include "sinew/model/scene_surface.hpp"

#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/io/surface_reader.hpp"
#include "sinew/mesh/inside_test.hpp"
#include "sinew/mesh/lattice.hpp"
#include "sinew/mesh/tetrahedralize_surface.hpp"
#include "sinew/mesh/voxelize.hpp"
#include "sinew/model/json_reader.hpp"

namespace sinew {
namespace {

std::filesystem::path existing_file(JsonObject& o, const std::string& key, const std::filesystem::path& folder) {
  const std::filesystem::path p = o.string(key);
  if (p.empty()) o.fail(key, "must name a surface file");
  const std::filesystem::path resolved = p.is_absolute() ? p : folder / p;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(resolved, ec))
    o.fail(key, fmt::format("surface file not found: {}{}", resolved.string(),
                            p.is_absolute() ? "" : " (relative paths start at the scene file's folder)"));
  return resolved;
}

}  // namespace

std::optional<std::filesystem::path> parse_embedded_surface(JsonObject& o, const std::filesystem::path& folder,
                                                            const std::optional<std::filesystem::path>& own_surface) {
  if (!o.has("embed")) return std::nullopt;
  if (o.raw("embed").is_string()) return existing_file(o, "embed", folder);
  if (!o.raw("embed").is_boolean()) o.fail("embed", "must be true, false or a surface file");
  if (!o.boolean("embed", false)) return std::nullopt;
  if (!own_surface) o.fail("embed", "true embeds the input surface of surface or tetrahedralize; name a surface file to embed in this mesh");
  return own_surface;
}

bool parse_surface_mesh(JsonObject& o, const std::filesystem::path& folder, MeshSpec& spec) {
  const bool voxels = o.has("surface"), tets = o.has("tetrahedralize");
  if (!voxels && !tets) return false;
  if (voxels && tets) o.fail("tetrahedralize", "give either surface (voxelise) or tetrahedralize, not both");
  for (const char* other : {"box", "cylinder", "sphere", "voxels", "file", "cells"})
    if (o.has(other)) o.fail(other, fmt::format("not allowed with {}", voxels ? "surface" : "tetrahedralize"));
  if (voxels) {
    const std::filesystem::path path = existing_file(o, "surface", folder);
    if (int(o.has("cell_size")) + int(o.has("resolution")) != 1) o.fail("", "give exactly one of cell_size or resolution");
    if (o.has("cell_size")) spec.cell_size = o.positive("cell_size");
    if (o.has("resolution")) spec.resolution = o.integer("resolution", 1);
    spec.source = SurfaceVoxels{path, o.boolean("non_manifold", false), std::nullopt};
    if (o.has("grid_origin")) std::get<SurfaceVoxels>(spec.source).grid_origin = o.vec3("grid_origin");
    spec.element = o.choice("element", {"hex", "tet"}, "hex") == "hex" ? ElementKind::Hex8 : ElementKind::Tet4;
  } else {
    const std::filesystem::path path = existing_file(o, "tetrahedralize", folder);
    for (const char* key : {"cell_size", "resolution", "non_manifold", "element", "grid_origin"})
      if (o.has(key)) o.fail(key, "not used by tetrahedralize (its size is max_edge)");
    spec.source = SurfaceTetrahedra{path, o.positive("max_edge")};
    spec.element = ElementKind::Tet4;
  }
  spec.embed = parse_embedded_surface(o, folder, voxels ? std::get<SurfaceVoxels>(spec.source).path
                                                          : std::get<SurfaceTetrahedra>(spec.source).path);
  o.finish();
  return true;
}

std::optional<VolumeMesh> build_surface_mesh(const MeshSpec& spec) {
  if (const auto* v = std::get_if<SurfaceVoxels>(&spec.source)) {
    const TriangleSurface surface = read_triangle_surface(v->path);
    VoxelizeOptions options;
    options.cell_size = spec.cell_size;
    options.resolution = spec.resolution;
    options.non_manifold = v->non_manifold;
    options.grid_origin = v->grid_origin;
    VolumeMesh mesh = voxelize_surface(InsideTest(surface), options);
    if (spec.element == ElementKind::Tet4) mesh = tetrahedralize_hexes(mesh);
    return mesh;
  }
  if (const auto* t = std::get_if<SurfaceTetrahedra>(&spec.source))
    return tetrahedralize_surface(read_triangle_surface(t->path), t->max_edge);
  return std::nullopt;
}

}  // namespace sinew
