#pragma once
// Regular hexahedral lattices: a box, or the cells of a grid that lie inside a shape given
// by a signed distance (negative inside) or a voxel occupancy predicate. Each keeps its grid
// (VolumeMesh::lattice); splitting into tetrahedra drops it.
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <string>

#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

// The most cells any lattice may have (scene shapes, voxel shapes, voxelised surfaces): far
// beyond what fits a workstation, and small enough that every vertex index fits an int.
inline constexpr std::int64_t kMaxLatticeCells = 50'000'000;

// Checks cell counts that came from input: each positive, and their product (in 64-bit
// arithmetic, so it cannot wrap) at most kMaxLatticeCells. `where` is the error context.
void check_lattice_cells(const Eigen::Vector3i& cells, const std::string& where);

// Cell counts for a lattice of extents `size` with cell size h: per axis round(size / h)
// (`ceil`: the smallest count that covers size, less 1e-9 so an exact multiple adds no layer), at least 1. The counts
// are formed in floating point and checked before any conversion to int, so a tiny h (1e-20)
// or a huge extent is an error naming `where`, never a wrapped count.
Eigen::Vector3i lattice_cell_counts(const Eigen::Vector3d& size, double h, bool ceil, const std::string& where);

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
