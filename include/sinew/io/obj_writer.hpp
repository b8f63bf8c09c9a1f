#pragma once
// Wavefront OBJ triangle meshes (positions and faces only) for renderers and quick looks at
// the deformed boundary. Written through write_file_atomically.
#include <Eigen/Core>
#include <filesystem>

#include "sinew/mesh/surface.hpp"
#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

// "v x y z" lines (shortest text that reads back to the same double), then "f a b c" with
// 1-based indices. Throws sinew::Error naming the file on an index out of range.
void write_obj(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices,
               const Eigen::MatrixXi& triangles);

// The boundary surface at positions x (x[3 v + i]): only the surface's vertices, renumbered
// in increasing volume-vertex order, and its outward triangles.
void write_surface_obj(const std::filesystem::path& path, const VolumeMesh& mesh,
                       const BoundarySurface& surface, const Eigen::VectorXd& x);

}  // namespace sinew
