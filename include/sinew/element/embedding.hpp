#pragma once
// Embedding of points (the vertices of a high-resolution render surface) in a volume mesh:
// each point is bound to the element containing it at rest, with trilinear weights in a
// hexahedron or barycentric weights in a tetrahedron, and follows the element as it deforms.
#include <Eigen/Core>
#include <vector>

#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

struct Embedding {
  Eigen::MatrixXi nodes;     // per point, the nodes of its element (nodes_per_element columns)
  Eigen::MatrixXd weights;   // per point, the shape-function values at its rest position (sum 1)
  std::vector<int> element;  // per point, the element it is bound to
  // Largest distance, in reference coordinates, by which a point lies outside its element
  // (0 when every point is inside one; a point outside the mesh is bound to the nearest
  // element and its weights extrapolate, which still reproduces affine motions exactly).
  double max_outside = 0.0;

  Eigen::Index num_points() const { return nodes.rows(); }
  // Deformed point positions for mesh positions x (x[3 v + i]).
  Eigen::MatrixX3d positions(const Eigen::VectorXd& x) const;
};

// Binds every row of `points` to an element of `mesh` (rest positions).
Embedding embed_points(const VolumeMesh& mesh, const Eigen::MatrixX3d& points);

}  // namespace sinew
