#pragma once
// A volume mesh of one element kind: rest positions and connectivity, plain Eigen types.
#include <Eigen/Core>
#include <string>

namespace sinew {

enum class ElementKind {
  Hex8,  // trilinear hexahedron, VTK_HEXAHEDRON node order
  Tet4,  // linear tetrahedron, VTK_TETRA node order
};
int nodes_per_element(ElementKind kind);
const char* to_string(ElementKind kind);

struct VolumeMesh {
  ElementKind kind = ElementKind::Hex8;
  Eigen::MatrixX3d vertices;  // rest positions, one row per vertex
  Eigen::MatrixXi elements;   // one row per element, nodes_per_element(kind) columns

  Eigen::Index num_vertices() const { return vertices.rows(); }
  Eigen::Index num_elements() const { return elements.rows(); }

  // Rejects out-of-range indices, repeated nodes and non-finite coordinates; the sinew::Error
  // names `source` and the first bad element. validate_mesh (element/mesh_validation.hpp) adds
  // the element shapes (inverted or degenerate elements), which needs the quadrature rules.
  void validate(const std::string& source) const;

  // Rest positions flattened as x[3 v + i].
  Eigen::VectorXd rest_positions() const;
};

}  // namespace sinew
