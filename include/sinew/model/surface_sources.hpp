#pragma once
// Scene mesh sources made from a closed triangle surface (docs/scene-format.md, "Surfaces"):
// a voxelised lattice or a Gmsh tetrahedralisation.
#include <Eigen/Core>
#include <filesystem>
#include <optional>

namespace sinew {

// {"surface": FILE, "cell_size" | "resolution", "non_manifold"}: mesh/voxelize.hpp.
struct SurfaceVoxels {
  std::filesystem::path path;  // resolved against the scene's folder
  bool non_manifold = false;
  std::optional<Eigen::Vector3d> grid_origin;  // "grid_origin": a point the grid planes pass through
};
// {"tetrahedralize": FILE, "max_edge"}: mesh/tetrahedralize_surface.hpp.
struct SurfaceTetrahedra {
  std::filesystem::path path;
  double max_edge = 0.0;
};

}  // namespace sinew
