#pragma once
// A volume mesh of one element kind: rest positions and connectivity, plain Eigen types.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "sinew/mesh/lattice_structure.hpp"

namespace sinew {

enum class ElementKind {
  Hex8,  // trilinear hexahedron, VTK_HEXAHEDRON node order
  Tet4,  // linear tetrahedron, VTK_TETRA node order
};
int nodes_per_element(ElementKind kind);
const char* to_string(ElementKind kind);

// A set of vertices a mesh file names: a Gmsh physical group, the vertices of its elements.
struct MeshGroup {
  std::string name;   // "" when the file gives the group no name
  int tag = 0;        // the file's number for the group (unique per dimension only)
  int dimension = 0;  // of its elements: 3 volume, 2 surface (triangles, quads), 1 curve, 0 point
  std::vector<int> vertices;  // sorted, unique
};

struct VolumeMesh {
  ElementKind kind = ElementKind::Hex8;
  Eigen::MatrixX3d vertices;  // rest positions, one row per vertex
  Eigen::MatrixXi elements;   // one row per element, nodes_per_element(kind) columns
  // The grid of a hexahedral lattice (mesh/lattice.hpp, mesh/voxelize.hpp), for solvers that
  // use it; absent for meshes read from files and for lattices split into tetrahedra.
  std::optional<LatticeStructure> lattice;
  // Vertex groups the mesh file defines (Gmsh physical groups); selectors pick them by name or
  // tag (mesh/selection.hpp). Empty for generated meshes and other formats.
  std::vector<MeshGroup> groups;

  Eigen::Index num_vertices() const { return vertices.rows(); }
  Eigen::Index num_elements() const { return elements.rows(); }

  // Rejects out-of-range indices, repeated nodes, non-finite coordinates and a lattice structure
  // that does not match the mesh; the sinew::Error
  // names `source` and the first bad element. validate_mesh (element/mesh_validation.hpp) adds
  // the element shapes (inverted or degenerate elements), which needs the quadrature rules.
  void validate(const std::string& source) const;

  // Rest positions flattened as x[3 v + i].
  Eigen::VectorXd rest_positions() const;
};

}  // namespace sinew
