#include "sinew/mesh/volume_mesh.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

int nodes_per_element(ElementKind kind) { return kind == ElementKind::Hex8 ? 8 : 4; }

const char* to_string(ElementKind kind) { return kind == ElementKind::Hex8 ? "hex8" : "tet4"; }

Eigen::VectorXd VolumeMesh::rest_positions() const {
  Eigen::VectorXd x(3 * num_vertices());
  for (Eigen::Index v = 0; v < num_vertices(); ++v) x.segment<3>(3 * v) = vertices.row(v).transpose();
  return x;
}

void VolumeMesh::validate(const std::string& source) const {
  const int n = nodes_per_element(kind);
  if (elements.cols() != n) {
    throw Error(fmt::format("{} elements need {} nodes, got {} columns", to_string(kind), n,
                            elements.cols()),
                source);
  }
  if (num_elements() == 0) throw Error("mesh has no elements", source);
  for (Eigen::Index v = 0; v < num_vertices(); ++v) {
    if (!vertices.row(v).allFinite()) {
      throw Error(fmt::format("vertex {} has a non-finite coordinate", v), source);
    }
  }
  for (Eigen::Index e = 0; e < num_elements(); ++e) {
    for (int a = 0; a < n; ++a) {
      const int v = elements(e, a);
      if (v < 0 || v >= num_vertices()) {
        throw Error(fmt::format("element {} refers to vertex {} (mesh has {} vertices)", e, v,
                                num_vertices()),
                    source);
      }
      for (int b = 0; b < a; ++b) {
        if (elements(e, b) == v) {
          throw Error(fmt::format("element {} repeats vertex {}", e, v), source);
        }
      }
    }
  }
}

}  // namespace sinew
