#pragma once
// VTK cell arrays (offsets, connectivity, cell types) to a single-kind VolumeMesh, shared by
// the legacy .vtk and the XML .vtu readers.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sinew/mesh/volume_mesh.hpp"

namespace sinew {

// VTK cell type ids Sinew reads (vtkCellType.h); both use the node order of VolumeMesh.
constexpr std::int64_t kVtkTetra = 10;
constexpr std::int64_t kVtkHexahedron = 12;

// A readable name of a VTK linear or quadratic cell type ("triangle", "wedge", ...).
std::string vtk_cell_type_name(std::int64_t type);

struct VtkCells {
  std::vector<std::int64_t> offsets;  // num_cells + 1 entries, offsets[0] = 0
  std::vector<std::int64_t> connectivity;
  std::vector<std::int64_t> types;    // num_cells entries
};

enum class VtkCellPart { Type, Nodes };

// Builds the mesh; `where(cell, part)` gives the sinew::Error context for a problem with a
// cell's type or node list (a file:line or an array name). Rejects other cell types, mixed
// hexahedra and tetrahedra, wrong node counts and point indices outside [0, points).
VolumeMesh vtk_cells_to_mesh(Eigen::MatrixX3d points, const VtkCells& cells,
                             const std::function<std::string(std::size_t, VtkCellPart)>& where);

}  // namespace sinew
