#include "sinew/mesh/selection.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "sinew/core/error.hpp"

namespace sinew {

std::vector<int> select_vertices(const Eigen::MatrixX3d& rest, const VertexSelector& selector,
                                 const std::string& context) {
  std::vector<int> out;
  // Tolerance relative to the model size, so selections on exact lattice planes are stable.
  const double scale = rest.rows() ? (rest.colwise().maxCoeff() - rest.colwise().minCoeff()).norm() : 1.0;
  const double tol = 1e-9 * std::max(scale, 1e-300);
  if (const auto* box = std::get_if<BoxSelector>(&selector)) {
    for (Eigen::Index v = 0; v < rest.rows(); ++v) {
      const Eigen::Vector3d p = rest.row(v).transpose();
      if (((p - box->lo).array() >= -tol).all() && ((box->hi - p).array() >= -tol).all()) out.push_back(static_cast<int>(v));
    }
  } else if (const auto* plane = std::get_if<PlaneSelector>(&selector)) {
    const double len = plane->normal.norm();
    if (!(len > 0.0)) throw Error("plane normal must be non-zero", context);
    const Eigen::Vector3d n = plane->normal / len;
    for (Eigen::Index v = 0; v < rest.rows(); ++v)
      if ((rest.row(v).transpose() - plane->point).dot(n) >= -tol) out.push_back(static_cast<int>(v));
  } else if (std::holds_alternative<GroupSelector>(selector)) {
    throw Error("a group selector needs the mesh's groups", context);
  } else {
    for (int v : std::get<IndexSelector>(selector).indices) {
      if (v < 0 || v >= rest.rows())
        throw Error(fmt::format("vertex index {} out of range (mesh has {} vertices)", v, rest.rows()), context);
      out.push_back(v);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (out.empty()) throw Error("selection contains no vertex", context);
  return out;
}

std::string describe(const MeshGroup& g) {
  static const char* kDimensions[] = {"point", "curve", "surface", "volume"};
  const char* dimension = g.dimension >= 0 && g.dimension <= 3 ? kDimensions[g.dimension] : "?";
  return g.name.empty() ? fmt::format("tag {} ({})", g.tag, dimension)
                        : fmt::format("'{}' (tag {}, {})", g.name, g.tag, dimension);
}

std::vector<int> select_vertices(const VolumeMesh& mesh, const VertexSelector& selector, const std::string& context) {
  const auto* group = std::get_if<GroupSelector>(&selector);
  if (!group) return select_vertices(mesh.vertices, selector, context);
  const std::string wanted = group->name ? fmt::format("named '{}'", *group->name) : fmt::format("with tag {}", *group->tag);
  const std::string in_dimension = group->dimension ? fmt::format(" of dimension {}", *group->dimension) : "";
  if (mesh.groups.empty())
    throw Error(fmt::format("no group {}{}: the mesh has no groups (they come from the physical groups of a Gmsh .msh file)",
                            wanted, in_dimension),
                context);
  std::vector<const MeshGroup*> found;
  for (const MeshGroup& g : mesh.groups)
    if ((group->name ? g.name == *group->name : g.tag == *group->tag) && (!group->dimension || g.dimension == *group->dimension))
      found.push_back(&g);
  auto list = [](const std::vector<const MeshGroup*>& groups) {
    std::string s;
    for (const MeshGroup* g : groups) s += (s.empty() ? "" : ", ") + describe(*g);
    return s;
  };
  if (found.empty()) {
    std::vector<const MeshGroup*> all;
    for (const MeshGroup& g : mesh.groups) all.push_back(&g);
    throw Error(fmt::format("no group {}{} in the mesh; its groups: {}", wanted, in_dimension, list(all)), context);
  }
  if (found.size() > 1)
    throw Error(fmt::format("{} groups {}: {}; add \"dimension\" to choose one", found.size(), wanted, list(found)), context);
  if (found[0]->vertices.empty()) throw Error(fmt::format("group {} has no vertices", describe(*found[0])), context);
  return found[0]->vertices;
}

}  // namespace sinew
