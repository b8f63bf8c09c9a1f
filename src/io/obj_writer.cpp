#include "sinew/io/obj_writer.hpp"

#include <fmt/format.h>
#include <ostream>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"

namespace sinew {

void write_obj(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices,
               const Eigen::MatrixXi& triangles) {
  if (triangles.cols() != 3 && triangles.rows() > 0) {
    throw Error(fmt::format("triangles have {} columns, expected 3", triangles.cols()), path.string());
  }
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      if (triangles(t, k) < 0 || triangles(t, k) >= vertices.rows()) {
        throw Error(fmt::format("triangle {} refers to vertex {} (there are {} vertices)", t,
                                triangles(t, k), vertices.rows()),
                    path.string());
      }
  write_file_atomically(path, [&](std::ostream& os) {
    // Formatted into one buffer: per-value iostream formatting is slow on large surfaces.
    fmt::memory_buffer text;
    for (Eigen::Index v = 0; v < vertices.rows(); ++v) {
      fmt::format_to(std::back_inserter(text), "v {} {} {}\n", vertices(v, 0), vertices(v, 1), vertices(v, 2));
    }
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
      fmt::format_to(std::back_inserter(text), "f {} {} {}\n", triangles(t, 0) + 1, triangles(t, 1) + 1,
                     triangles(t, 2) + 1);
    }
    os.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

void write_surface_obj(const std::filesystem::path& path, const VolumeMesh& mesh,
                       const BoundarySurface& surface, const Eigen::VectorXd& x) {
  const Eigen::Index nv = mesh.num_vertices();
  if (x.size() != 3 * nv) {
    throw Error(fmt::format("positions have {} values, expected 3 x {} vertices", x.size(), nv),
                path.string());
  }
  // Volume vertex -> surface vertex number.
  Eigen::VectorXi local = Eigen::VectorXi::Constant(nv, -1);
  Eigen::MatrixX3d vertices(static_cast<Eigen::Index>(surface.vertices.size()), 3);
  for (std::size_t i = 0; i < surface.vertices.size(); ++i) {
    const int v = surface.vertices[i];
    if (v < 0 || v >= nv) {
      throw Error(fmt::format("surface vertex {} is not a mesh vertex", v), path.string());
    }
    local[v] = static_cast<int>(i);
    vertices.row(static_cast<Eigen::Index>(i)) = x.segment<3>(3 * v).transpose();
  }
  Eigen::MatrixXi triangles(surface.triangles.rows(), 3);
  for (Eigen::Index t = 0; t < surface.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int v = surface.triangles(t, k);
      if (v < 0 || v >= nv || local[v] < 0) {
        throw Error(fmt::format("surface triangle {} uses vertex {}, which is not a surface vertex", t, v),
                    path.string());
      }
      triangles(t, k) = local[v];
    }
  write_obj(path, vertices, triangles);
}

}  // namespace sinew
