#include "sinew/io/ply_writer.hpp"

#include <fmt/format.h>
#include <ostream>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"

namespace sinew {

void write_ply(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices, const Eigen::MatrixXi& triangles) {
  if (triangles.cols() != 3 && triangles.rows() > 0)
    throw Error(fmt::format("triangles have {} columns, expected 3", triangles.cols()), path.string());
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      if (triangles(t, k) < 0 || triangles(t, k) >= vertices.rows())
        throw Error(fmt::format("triangle {} refers to vertex {} (there are {} vertices)", t, triangles(t, k),
                                vertices.rows()),
                    path.string());
  write_file_atomically(path, [&](std::ostream& os) {
    fmt::memory_buffer text;
    auto out = std::back_inserter(text);
    fmt::format_to(out,
                   "ply\nformat ascii 1.0\ncomment written by Sinew\nelement vertex {}\nproperty double x\n"
                   "property double y\nproperty double z\nelement face {}\nproperty list uchar int vertex_indices\n"
                   "end_header\n",
                   vertices.rows(), triangles.rows());
    for (Eigen::Index v = 0; v < vertices.rows(); ++v)
      fmt::format_to(out, "{} {} {}\n", vertices(v, 0), vertices(v, 1), vertices(v, 2));
    for (Eigen::Index t = 0; t < triangles.rows(); ++t)
      fmt::format_to(out, "3 {} {} {}\n", triangles(t, 0), triangles(t, 1), triangles(t, 2));
    os.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

}  // namespace sinew
