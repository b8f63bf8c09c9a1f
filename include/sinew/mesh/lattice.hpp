#pragma once
// Regular hexahedral lattices: a box, or the cells of a grid that lie inside a shape given
// by a signed distance (negative inside) or a voxel occupancy predicate. Each keeps its grid
// (VolumeMesh::lattice); splitting into tetrahedra drops it.
#include <Eigen/Geometry>
#include <functional>

#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

// cells(i) > 0 cells along axis i between lo and hi.
VolumeMesh box_lattice(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Eigen::Vector3i& cells);

// Keeps the cells of the grid over `bounds` (cell counts `cells`) whose centre satisfies
// `inside`; unused vertices are dropped. Throws if no cell is kept.
VolumeMesh occupancy_lattice(const Eigen::AlignedBox3d& bounds, const Eigen::Vector3i& cells,
                             const std::function<bool(const Eigen::Vector3d&)>& inside);

// Signed distance shapes (negative inside).
using SignedDistance = std::function<double(const Eigen::Vector3d&)>;
SignedDistance sphere_sdf(const Eigen::Vector3d& center, double radius);
// Cylinder along `axis` (0, 1, 2) centred at `center`.
SignedDistance cylinder_sdf(const Eigen::Vector3d& center, double radius, double length, int axis);
SignedDistance box_sdf(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

// Splits every hexahedron into six tetrahedra around its main diagonal (Kuhn/Freudenthal).
VolumeMesh tetrahedralize_hexes(const VolumeMesh& hexes);

}  // namespace sinew
