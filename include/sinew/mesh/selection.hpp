#pragma once
// Vertex selections for boundary conditions and loads: inside a box, on one side of a plane,
// or an explicit index list.
#include <Eigen/Core>
#include <string>
#include <variant>
#include <vector>

namespace sinew {

struct BoxSelector {
  Eigen::Vector3d lo, hi;  // inclusive, with a small tolerance
};
struct PlaneSelector {
  Eigen::Vector3d point, normal;  // vertices with (p - point) . normal >= 0 (small tolerance)
};
struct IndexSelector {
  std::vector<int> indices;
};
using VertexSelector = std::variant<BoxSelector, PlaneSelector, IndexSelector>;

// Sorted, unique vertex indices. Throws a sinew::Error (with `context`) if the selection is
// empty or an index is out of range: a boundary condition that selects nothing is a mistake.
std::vector<int> select_vertices(const Eigen::MatrixX3d& rest, const VertexSelector& selector,
                                 const std::string& context);

}  // namespace sinew
