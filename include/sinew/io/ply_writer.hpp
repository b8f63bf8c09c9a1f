#pragma once
// ASCII PLY surfaces (positions, faces and optional per-vertex scalar properties such as J or
// a stress measure), written through write_file_atomically.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sinew/mesh/polygon_surface.hpp"

namespace sinew {

// Per-vertex scalars written as "property double NAME" after x y z, in the order given.
using PlyVertexScalars = std::vector<std::pair<std::string, Eigen::VectorXd>>;

// "element vertex" rows as doubles (shortest text that reads back to the same value), then
// "element face" rows "3 a b c" with 0-based indices. Throws sinew::Error naming the file on
// an index out of range, or on a scalar property of the wrong size, a name that is empty,
// repeated, x/y/z or not a plain identifier.
void write_ply(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices, const Eigen::MatrixXi& triangles,
               const PlyVertexScalars& scalars = {});

// The polygons of a render surface at `positions` (quads stay quads; texture coordinates,
// normals, groups and materials are not part of this file: the OBJ keeps them).
void write_ply(const std::filesystem::path& path, const PolygonSurface& surface, const Eigen::MatrixX3d& positions,
               const PlyVertexScalars& scalars = {});

}  // namespace sinew
