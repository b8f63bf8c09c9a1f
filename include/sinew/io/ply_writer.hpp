#pragma once
// ASCII PLY triangle meshes (positions and faces), written through write_file_atomically.
#include <Eigen/Core>
#include <filesystem>

namespace sinew {

// "element vertex" rows as doubles (shortest text that reads back to the same value), then
// "element face" rows "3 a b c" with 0-based indices. Throws sinew::Error naming the file on
// an index out of range.
void write_ply(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices, const Eigen::MatrixXi& triangles);

}  // namespace sinew
