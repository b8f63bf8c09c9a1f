#pragma once
// Voxelisation of a closed surface into a hexahedral lattice (Hex8 VolumeMesh, the same node
// order as mesh/lattice.hpp): a cell is kept when its centre is inside the surface or the cell
// crosses the surface, so the kept cells cover the whole solid and every surface point lies
// in a kept cell (what embedding needs).
#include <optional>

#include "sinew/mesh/inside_test.hpp"
#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

struct VoxelizeOptions {
  // Exactly one: the cell edge length, or the number of cells along the longest side of the
  // surface's bounding box.
  std::optional<double> cell_size;
  std::optional<int> resolution;
  // Keep cells that cross the surface (not only those whose centre is inside).
  bool keep_crossing = true;
  // Mitchell et al. 2015 (non-manifold level sets, cited by paper 000): a lattice vertex gets
  // one copy per group of its kept cells connected through shared faces, so parts that touch
  // only along an edge or at a vertex are not glued together.
  bool non_manifold = false;
  // A point the lattice's grid planes pass through (the lattice then starts at the largest grid
  // point at or below the bounding-box minimum). Rigs want planes through their bone axes, so
  // that a thin bone binds a ring of vertices around its axis rather than one line or none.
  std::optional<Eigen::Vector3d> grid_origin;
};

// The lattice starts at the surface's bounding-box minimum (or on options.grid_origin's grid); a sinew::Error says why when the
// options are invalid, the lattice would be too large or no cell is kept. The mesh keeps its grid
// (VolumeMesh::lattice), with the copies of non-manifold vertices numbered.
VolumeMesh voxelize_surface(const InsideTest& shape, const VoxelizeOptions& options);

// The lattice's cell size for `options` over `bounds` (shared with the scene reader).
double voxel_cell_size(const Eigen::AlignedBox3d& bounds, const VoxelizeOptions& options);

}  // namespace sinew
