#pragma once
// The boundary surface of a volume mesh: faces that belong to exactly one element, with
// outward orientation. Quads of hexahedra are kept as quads and also split into triangles.
#include <Eigen/Core>
#include <vector>

#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

struct BoundarySurface {
  // Faces as volume-mesh vertex indices, outward (counter-clockwise seen from outside).
  std::vector<std::vector<int>> faces;  // 4 nodes (hex) or 3 nodes (tet)
  std::vector<Eigen::Index> face_element;  // owning element
  Eigen::MatrixXi triangles;               // faces split into triangles (rows of 3 indices)
  std::vector<int> vertices;               // sorted volume vertices on the boundary
};

BoundarySurface boundary_surface(const VolumeMesh& mesh);

// The faces of `surface` whose vertices are all in `selected` (vertex ids of a mesh with
// `num_vertices` vertices), as they are (outward, 3 or 4 nodes).
std::vector<std::vector<int>> faces_within(const BoundarySurface& surface, const std::vector<int>& selected,
                                           Eigen::Index num_vertices);

}  // namespace sinew
