#include "sinew/io/vtk_cells.hpp"

#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

std::string vtk_cell_type_name(std::int64_t type) {
  switch (type) {
    case 1: return "vertex";
    case 2: return "poly-vertex";
    case 3: return "line";
    case 4: return "poly-line";
    case 5: return "triangle";
    case 6: return "triangle strip";
    case 7: return "polygon";
    case 8: return "pixel";
    case 9: return "quad";
    case 10: return "tetra";
    case 11: return "voxel";
    case 12: return "hexahedron";
    case 13: return "wedge";
    case 14: return "pyramid";
    case 21: return "quadratic edge";
    case 22: return "quadratic triangle";
    case 23: return "quadratic quad";
    case 24: return "quadratic tetra";
    case 25: return "quadratic hexahedron";
    case 42: return "polyhedron";
    default: return "unknown";
  }
}

VolumeMesh vtk_cells_to_mesh(Eigen::MatrixX3d points, const VtkCells& cells,
                             const std::function<std::string(std::size_t, VtkCellPart)>& where) {
  const std::size_t n = cells.types.size();
  if (cells.offsets.size() != n + 1) {
    throw Error(fmt::format("{} cell types but {} cell node lists", n, cells.offsets.size() - 1),
                where(0, VtkCellPart::Nodes));
  }
  if (n == 0) throw Error("the file has no cells", where(0, VtkCellPart::Type));
  VolumeMesh mesh;
  for (std::size_t c = 0; c < n; ++c) {
    const std::int64_t type = cells.types[c];
    if (type != kVtkHexahedron && type != kVtkTetra) {
      throw Error(fmt::format("cell {} has VTK type {} ({}); only 12 (hexahedron) and 10 (tetra) are supported",
                              c, type, vtk_cell_type_name(type)),
                  where(c, VtkCellPart::Type));
    }
    const ElementKind kind = type == kVtkHexahedron ? ElementKind::Hex8 : ElementKind::Tet4;
    if (c == 0) {
      mesh.kind = kind;
    } else if (kind != mesh.kind) {
      throw Error(fmt::format("cell {} is a {} but cell 0 is a {}: meshes mixing hexahedra and "
                              "tetrahedra are not supported",
                              c, vtk_cell_type_name(type), to_string(mesh.kind)),
                  where(c, VtkCellPart::Type));
    }
  }
  const int nodes = nodes_per_element(mesh.kind);
  const auto num_points = static_cast<std::int64_t>(points.rows());
  mesh.elements.resize(static_cast<Eigen::Index>(n), nodes);
  for (std::size_t c = 0; c < n; ++c) {
    const std::int64_t begin = cells.offsets[c], end = cells.offsets[c + 1];
    if (begin < 0 || end < begin || end > static_cast<std::int64_t>(cells.connectivity.size())) {
      throw Error(fmt::format("cell {} has invalid offsets [{}, {}) into {} connectivity entries", c,
                              begin, end, cells.connectivity.size()),
                  where(c, VtkCellPart::Nodes));
    }
    if (end - begin != nodes) {
      throw Error(fmt::format("cell {} is a {} with {} nodes, expected {}", c,
                              vtk_cell_type_name(cells.types[c]), end - begin, nodes),
                  where(c, VtkCellPart::Nodes));
    }
    for (int a = 0; a < nodes; ++a) {
      const std::int64_t p = cells.connectivity[static_cast<std::size_t>(begin + a)];
      if (p < 0 || p >= num_points) {
        throw Error(fmt::format("cell {} refers to point {}, outside [0, {})", c, p, num_points),
                    where(c, VtkCellPart::Nodes));
      }
      mesh.elements(static_cast<Eigen::Index>(c), a) = static_cast<int>(p);
    }
  }
  mesh.vertices = std::move(points);
  return mesh;
}

}  // namespace sinew
