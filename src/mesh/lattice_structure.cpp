#include "sinew/mesh/lattice_structure.hpp"

#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

void LatticeStructure::validate(Eigen::Index vertices, Eigen::Index elements, const std::string& source) const {
  if ((cells.array() <= 0).any() || !(spacing.array() > 0.0).all() || !origin.allFinite())
    throw Error("lattice structure has no grid (cells and spacing must be positive)", source);
  if (vertex_point.rows() != vertices || vertex_copy.size() != vertices)
    throw Error(fmt::format("lattice structure lists {} vertices, the mesh has {}", vertex_point.rows(), vertices),
                source);
  if (element_cell.rows() != elements)
    throw Error(fmt::format("lattice structure lists {} cells, the mesh has {} elements", element_cell.rows(), elements),
                source);
  for (Eigen::Index v = 0; v < vertices; ++v)
    for (int a = 0; a < 3; ++a)
      if (vertex_point(v, a) < 0 || vertex_point(v, a) > cells(a) || vertex_copy(v) < 0)
        throw Error(fmt::format("vertex {} lies outside the lattice grid", v), source);
  for (Eigen::Index e = 0; e < elements; ++e)
    for (int a = 0; a < 3; ++a)
      if (element_cell(e, a) < 0 || element_cell(e, a) >= cells(a))
        throw Error(fmt::format("element {} lies outside the lattice grid", e), source);
}

}  // namespace sinew
