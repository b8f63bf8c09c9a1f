#pragma once
// Triangle surface input: Wavefront OBJ, STL (ASCII or binary), PLY (ASCII or binary) and OFF,
// parsed by CGAL's polygon-soup readers (CGAL::IO, docs/surfaces.md says why CGAL). CGAL
// reports only success or failure, so ASCII files are first scanned line by line: a NaN, a
// missing number, an index out of range or a file that ends early is reported with the file
// and line. Polygons with more than three corners are split into a fan of triangles.
#include <filesystem>

#include "sinew/mesh/triangle_surface.hpp"

namespace sinew {

// Picks the format by extension (case-insensitive) and validates the surface
// (TriangleSurface::validate with `require_closed`); every problem is a sinew::Error whose
// context names the file and, where there is one, the line.
TriangleSurface read_triangle_surface(const std::filesystem::path& path, bool require_closed = true);

}  // namespace sinew
