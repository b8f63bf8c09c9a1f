#include "sinew/io/ply_writer.hpp"

#include <fmt/format.h>
#include <ostream>
#include <set>

#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"

namespace sinew {
namespace {

void check_scalars(const PlyVertexScalars& scalars, Eigen::Index vertices, const std::string& where) {
  std::set<std::string> names{"x", "y", "z"};
  for (const auto& [name, values] : scalars) {
    const bool identifier = !name.empty() && name.find_first_not_of(
        "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") == std::string::npos;
    if (!identifier) throw Error(fmt::format("vertex property name '{}' is not a plain identifier", name), where);
    if (!names.insert(name).second) throw Error(fmt::format("vertex property '{}' is repeated or reserved", name), where);
    if (values.size() != vertices)
      throw Error(fmt::format("vertex property '{}' has {} values, expected {}", name, values.size(), vertices), where);
  }
}

// Faces as corner lists: face f is corners [start[f], start[f + 1]).
void write_faces_ply(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices, const std::vector<int>& start,
                     const std::vector<int>& corners, const PlyVertexScalars& scalars) {
  const std::string where = path.string();
  check_scalars(scalars, vertices.rows(), where);
  const size_t faces = start.size() - 1;
  for (size_t f = 0; f < faces; ++f) {
    if (start[f + 1] - start[f] > 255) throw Error(fmt::format("face {} has over 255 corners", f), where);
    for (int c = start[f]; c < start[f + 1]; ++c)
      if (corners[c] < 0 || corners[c] >= vertices.rows())
        throw Error(fmt::format("face {} refers to vertex {} (there are {} vertices)", f, corners[c], vertices.rows()), where);
  }
  write_file_atomically(path, [&](std::ostream& os) {
    fmt::memory_buffer text;
    auto out = std::back_inserter(text);
    fmt::format_to(out, "ply\nformat ascii 1.0\ncomment written by Sinew\nelement vertex {}\nproperty double x\n"
                        "property double y\nproperty double z\n", vertices.rows());
    for (const auto& [name, values] : scalars) fmt::format_to(out, "property double {}\n", name);
    fmt::format_to(out, "element face {}\nproperty list uchar int vertex_indices\nend_header\n", faces);
    for (Eigen::Index v = 0; v < vertices.rows(); ++v) {
      fmt::format_to(out, "{} {} {}", vertices(v, 0), vertices(v, 1), vertices(v, 2));
      for (const auto& [name, values] : scalars) fmt::format_to(out, " {}", values(v));
      fmt::format_to(out, "\n");
    }
    for (size_t f = 0; f < faces; ++f) {
      fmt::format_to(out, "{}", start[f + 1] - start[f]);
      for (int c = start[f]; c < start[f + 1]; ++c) fmt::format_to(out, " {}", corners[c]);
      fmt::format_to(out, "\n");
    }
    os.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

}  // namespace

void write_ply(const std::filesystem::path& path, const Eigen::MatrixX3d& vertices, const Eigen::MatrixXi& triangles,
               const PlyVertexScalars& scalars) {
  if (triangles.cols() != 3 && triangles.rows() > 0)
    throw Error(fmt::format("triangles have {} columns, expected 3", triangles.cols()), path.string());
  std::vector<int> start(static_cast<size_t>(triangles.rows()) + 1), corners(static_cast<size_t>(triangles.size()));
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    start[static_cast<size_t>(t + 1)] = static_cast<int>(3 * (t + 1));
    for (int k = 0; k < 3; ++k) corners[static_cast<size_t>(3 * t + k)] = triangles(t, k);
  }
  write_faces_ply(path, vertices, start, corners, scalars);
}

void write_ply(const std::filesystem::path& path, const PolygonSurface& surface, const Eigen::MatrixX3d& positions,
               const PlyVertexScalars& scalars) {
  surface.validate(path.string());
  if (positions.rows() != surface.num_positions())
    throw Error(fmt::format("{} positions given for a surface of {} vertices", positions.rows(), surface.num_positions()),
                path.string());
  std::vector<int> corners;
  corners.reserve(surface.corners.size());
  for (const auto& c : surface.corners) corners.push_back(c.position);
  write_faces_ply(path, positions, surface.face_start, corners, scalars);
}

}  // namespace sinew
