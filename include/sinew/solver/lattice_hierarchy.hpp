#pragma once
// The hierarchy of coarsened lattices geometric multigrid works on. A level is a set of cells
// of one grid, each with its eight corner vertices; the next level's grid has cells twice as
// large. The cells of a level that fall into one coarse grid cell are split into their connected
// components (cells sharing a vertex), and each component becomes a coarse cell of its own, so
// that parts of the body that only meet on a grid cell's boundary, or are separate copies of a
// non-manifold vertex, are not tied together by the coarse space. Corner vertices of coarse
// cells are merged where a fine vertex lies on both cells with a non-zero interpolation weight
// from that corner; fine vertices interpolate trilinearly from the corners of a coarse cell that
// contains them. Partially filled coarse cells are just coarse cells with fewer fine cells.
#include <Eigen/Core>
#include <array>
#include <vector>

#include "sinew/linalg/vertex_interpolation.hpp"
#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

struct LatticeLevel {
  std::vector<Eigen::Vector3i> vertex_point;  // grid point of each vertex, on this level's grid
  std::vector<Eigen::Vector3i> cell;          // grid cell of each cell
  std::vector<std::array<int, 8>> corners;    // corner vertex of each cell, at index bx + 2 by + 4 bz
  Eigen::Index vertices() const { return static_cast<Eigen::Index>(vertex_point.size()); }
};

// The finest level: the mesh's hexahedra on its lattice grid; a sinew::Error if the mesh has no
// lattice structure or an element's nodes are not its cell's corners.
LatticeLevel lattice_level(const VolumeMesh& mesh);

// The next coarser level and the interpolation from it to `fine` (prepared: transpose built).
LatticeLevel coarsen(const LatticeLevel& fine, VertexInterpolation& interpolation);

struct LatticeHierarchy {
  std::vector<LatticeLevel> levels;                 // levels[0] is the mesh
  std::vector<VertexInterpolation> interpolations;  // interpolations[l]: level l + 1 to level l
};

// Coarsens until a level has at most `coarsest_vertices` vertices, `max_levels` levels exist, or
// a coarsening no longer shrinks the level by at least a quarter.
LatticeHierarchy lattice_hierarchy(const VolumeMesh& mesh, Eigen::Index coarsest_vertices, int max_levels);

}  // namespace sinew
