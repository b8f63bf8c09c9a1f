#pragma once
// Wavefront OBJ render surfaces read as they are (docs/file-formats.md, "Render surfaces"):
// polygons keep their corners, and "vt", "vn", "g", "o", "usemtl", "mtllib" and "s" are kept
// (io/surface_reader.hpp, by contrast, reads closed triangle surfaces for meshing).
#include <filesystem>

#include "sinew/mesh/polygon_surface.hpp"

namespace sinew {

// Reads "v x y z [w]" (w and vertex colours dropped), "vt u [v [w]]", "vn x y z",
// "f v[/vt][/vn] ..." (1-based or negative = relative indices, at least three corners),
// "g", "o", "usemtl", "mtllib", "s N|off". Points, lines, curves and other statements are
// skipped (they carry no surface). Every problem (a missing or non-finite number, an index out
// of range or zero, a face with fewer than three corners, no face at all) is a sinew::Error
// whose context is "file:line".
PolygonSurface read_obj_polygon_surface(const std::filesystem::path& path);

}  // namespace sinew
