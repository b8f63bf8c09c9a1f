#pragma once
// Writes a render surface (mesh/polygon_surface.hpp) as Wavefront OBJ at new positions with its
// texture coordinates, groups, objects, materials, smoothing groups and polygons as read, and
// copies its material libraries beside the output (docs/file-formats.md, "Render surfaces").
#include <Eigen/Core>
#include <filesystem>

#include "sinew/mesh/polygon_surface.hpp"

namespace sinew {

enum class ObjNormals {
  // Input normals are recomputed at the new positions: corners that shared a (vertex, normal)
  // pair in the input share one normal, the area-weighted average of their faces' normals, so
  // smooth vertices stay smooth and hard edges (split normals) stay hard.
  Recompute,
  Omit,  // no "vn" at all (a renderer then derives normals from the smoothing groups)
};

struct ObjWriteOptions {
  ObjNormals normals = ObjNormals::Recompute;
  // "o" statements split an OBJ into several objects on import; a point cache (io/point_cache.hpp)
  // must apply to one object, so its rest OBJ leaves them out.
  bool objects = true;
};

// `positions` has one row per surface position. Written atomically; a sinew::Error names the
// file on a size mismatch or an invalid surface.
void write_obj_polygon_surface(const std::filesystem::path& path, const PolygonSurface& surface,
                               const Eigen::MatrixX3d& positions, const ObjWriteOptions& options = {});

// Copies every "mtllib" file of `surface` (resolved against the folder of `source_obj`) into
// `out_dir` under the same relative name, once per run. Texture maps named with a relative
// path in the library are rewritten to the absolute path of the source file, so the copy still
// finds them. A missing library is a sinew::Error naming the OBJ and the library.
void copy_material_libraries(const PolygonSurface& surface, const std::filesystem::path& source_obj,
                             const std::filesystem::path& out_dir);

}  // namespace sinew
