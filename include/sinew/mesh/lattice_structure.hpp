#pragma once
// The grid a hexahedral lattice was cut from, kept next to its mesh so that solvers can use it
// (geometric multigrid coarsens on it): the grid's cell counts, origin and spacing, the grid point
// of every vertex and the grid cell of every element. A voxelised lattice with the non-manifold
// option has several vertices on one grid point (one per face-connected group of cells around
// it); `vertex_copy` numbers them.
#include <Eigen/Core>
#include <string>

namespace sinew {

struct LatticeStructure {
  Eigen::Vector3i cells = Eigen::Vector3i::Zero();    // grid cells along x, y, z
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();   // rest position of grid point (0, 0, 0)
  Eigen::Vector3d spacing = Eigen::Vector3d::Zero();  // cell edge lengths along x, y, z
  Eigen::MatrixX3i vertex_point;  // per vertex: its grid point (i, j, k), 0 <= i <= cells(0)
  Eigen::VectorXi vertex_copy;    // per vertex: which copy of its grid point (0 unless non-manifold)
  Eigen::MatrixX3i element_cell;  // per element: its grid cell (the grid point of its node 0)
  bool non_manifold = false;      // whether a grid point may hold more than one vertex

  // Rest position of grid point p.
  Eigen::Vector3d position(const Eigen::Vector3i& p) const {
    return origin + spacing.cwiseProduct(p.cast<double>());
  }
  // Index of grid point p in x-fastest order over (cells + 1) points per axis.
  Eigen::Index point_index(const Eigen::Vector3i& p) const {
    return (static_cast<Eigen::Index>(p(2)) * (cells(1) + 1) + p(1)) * (cells(0) + 1) + p(0);
  }
  // Index of grid cell c in x-fastest order.
  Eigen::Index cell_index(const Eigen::Vector3i& c) const {
    return (static_cast<Eigen::Index>(c(2)) * cells(1) + c(1)) * cells(0) + c(0);
  }

  // Throws a sinew::Error naming `source` when the sizes do not match a mesh of `vertices` and
  // `elements` or a grid point or cell lies outside the grid.
  void validate(Eigen::Index vertices, Eigen::Index elements, const std::string& source) const;
};

}  // namespace sinew
