#pragma once
// Vertex selections for boundary conditions and loads: inside a box, on one side of a plane,
// an explicit index list, or a group the mesh file defines (a Gmsh physical group).
#include <Eigen/Core>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "sinew/mesh/volume_mesh.hpp"

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
// A mesh group (VolumeMesh::groups) by name or by tag; `dimension` tells apart groups of
// different dimensions that share the tag or name.
struct GroupSelector {
  std::optional<std::string> name;
  std::optional<int> tag;
  std::optional<int> dimension;
};
using VertexSelector = std::variant<BoxSelector, PlaneSelector, IndexSelector, GroupSelector>;

// Sorted, unique vertex indices. Throws a sinew::Error (with `context`) if the selection is
// empty or an index is out of range: a boundary condition that selects nothing is a mistake.
std::vector<int> select_vertices(const VolumeMesh& mesh, const VertexSelector& selector, const std::string& context);
// The same on rest positions alone; a group selector is then an error (it needs the mesh).
std::vector<int> select_vertices(const Eigen::MatrixX3d& rest, const VertexSelector& selector,
                                 const std::string& context);

// "'name' (tag 3, surface)" or "tag 3 (surface)": how messages name a group.
std::string describe(const MeshGroup& group);

}  // namespace sinew
