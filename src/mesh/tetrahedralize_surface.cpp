#include "sinew/mesh/tetrahedralize_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <mutex>
#include <queue>
#include <unordered_map>
#include <vector>

#include "gmsh_module_loader.hpp"
#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// Gmsh keeps one global model: calls are serialised.
std::mutex gmsh_mutex;

}  // namespace

TriangleSurface bisect_long_edges(const TriangleSurface& surface, double max_edge, Eigen::Index max_faces) {
  using Edge = std::pair<int, int>;  // (smaller, larger) vertex index
  const auto edge = [](int a, int b) { return a < b ? Edge{a, b} : Edge{b, a}; };
  std::vector<Eigen::Vector3d> vertices;
  for (Eigen::Index v = 0; v < surface.num_vertices(); ++v) vertices.push_back(surface.vertices.row(v).transpose());
  std::vector<std::array<int, 3>> faces;
  for (Eigen::Index f = 0; f < surface.num_faces(); ++f) faces.push_back({surface.faces(f, 0), surface.faces(f, 1), surface.faces(f, 2)});
  const auto length = [&](const Edge& e) { return (vertices[e.first] - vertices[e.second]).norm(); };

  std::map<Edge, std::vector<int>> faces_of;  // the faces that hold each edge
  std::priority_queue<std::pair<double, Edge>> longest;
  const auto add = [&](int a, int b, int f) {
    const Edge e = edge(a, b);
    faces_of[e].push_back(f);
    if (const double l = length(e); l > max_edge) longest.push({l, e});  // pushed once per face; popped once
  };
  for (int f = 0; f < static_cast<int>(faces.size()); ++f)
    for (int k = 0; k < 3; ++k) add(faces[f][k], faces[f][(k + 1) % 3], f);

  while (!longest.empty()) {
    const Edge e = longest.top().second;
    longest.pop();
    const auto it = faces_of.find(e);
    if (it == faces_of.end()) continue;  // already split
    const std::vector<int> incident = std::move(it->second);
    faces_of.erase(it);
    const int m = static_cast<int>(vertices.size());
    vertices.push_back(0.5 * (vertices[e.first] + vertices[e.second]));
    for (const int f : incident) {
      if (static_cast<Eigen::Index>(faces.size()) >= max_faces)
        throw Error(fmt::format("max_edge {} is too small for this surface: splitting its edges to that length needs "
                                "more than {} triangles",
                                max_edge, max_faces),
                    "tetrahedralize");
      // (a, b, c) with edge (a, b) becomes (a, m, c) and (m, b, c): both keep the orientation.
      int k = 0;
      while (edge(faces[f][k], faces[f][(k + 1) % 3]) != e) ++k;
      const int a = faces[f][k], b = faces[f][(k + 1) % 3], c = faces[f][(k + 2) % 3];
      const int g = static_cast<int>(faces.size());
      faces[f] = {a, m, c};
      faces.push_back({m, b, c});
      auto& bc = faces_of[edge(b, c)];
      std::replace(bc.begin(), bc.end(), f, g);
      add(a, m, f);
      add(m, b, g);
      add(m, c, f);
      faces_of[edge(m, c)].push_back(g);  // (m, c) is shared by both halves; queued once above
    }
  }
  TriangleSurface out;
  out.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t v = 0; v < vertices.size(); ++v) out.vertices.row(static_cast<Eigen::Index>(v)) = vertices[v].transpose();
  out.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < 3; ++k) out.faces(static_cast<Eigen::Index>(f), k) = faces[f][k];
  return out;
}

VolumeMesh tetrahedralize_surface(const TriangleSurface& input, double max_edge) {
  const std::string where = "tetrahedralize";
  if (!(max_edge > 0.0 && std::isfinite(max_edge)))
    throw Error(fmt::format("max_edge must be a positive finite number, got {}", max_edge), where);
  input.validate(where, true);
  const SurfaceTopology topology = surface_topology(input);
  if (!topology.watertight())
    throw Error(fmt::format("Gmsh needs a 2-manifold surface; this one has {} edges shared by more than two faces",
                            topology.nonmanifold_edges),
                where);
  // Gmsh keeps the boundary triangles and sizes the inside from them, so edges longer than
  // max_edge are split first, in their own plane: the boundary is then that split surface, on
  // which every input vertex (and so an embedded render surface) still lies exactly.
  const TriangleSurface surface = bisect_long_edges(input, max_edge);
  gmsh_module::Input in;
  in.max_edge = max_edge;
  in.coords.reserve(3 * static_cast<size_t>(surface.num_vertices()));
  for (Eigen::Index v = 0; v < surface.num_vertices(); ++v)
    for (int i = 0; i < 3; ++i) in.coords.push_back(surface.vertices(v, i));
  for (Eigen::Index f = 0; f < surface.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) in.triangles.push_back(static_cast<std::size_t>(surface.faces(f, k) + 1));
  const gmsh_module::TetrahedralizeFn gmsh_tetrahedralize = load_gmsh_module();
  gmsh_module::Output out;
  {
    std::lock_guard lock(gmsh_mutex);
    gmsh_tetrahedralize(in, out);
  }
  if (!out.error.empty()) throw Error(fmt::format("Gmsh failed: {}", out.error), where);
  if (out.tet_nodes.empty()) throw Error("Gmsh produced no tetrahedra", where);
  if (out.tet_nodes.size() % 4 != 0 || out.node_coords.size() != 3 * out.node_tags.size())
    throw Error("Gmsh returned inconsistent arrays", where);
  VolumeMesh mesh;
  mesh.kind = ElementKind::Tet4;
  // Only the nodes tetrahedra use, numbered in first-use order.
  std::unordered_map<std::size_t, std::size_t> position_of;
  for (std::size_t i = 0; i < out.node_tags.size(); ++i) position_of[out.node_tags[i]] = i;
  std::unordered_map<std::size_t, int> index_of;
  std::vector<std::size_t> used;
  const std::size_t tets = out.tet_nodes.size() / 4;
  mesh.elements.resize(static_cast<Eigen::Index>(tets), 4);
  for (std::size_t e = 0; e < tets; ++e)
    for (int a = 0; a < 4; ++a) {
      const std::size_t tag = out.tet_nodes[4 * e + a];
      auto [it, fresh] = index_of.try_emplace(tag, static_cast<int>(used.size()));
      if (fresh) used.push_back(tag);
      mesh.elements(static_cast<Eigen::Index>(e), a) = it->second;
    }
  mesh.vertices.resize(static_cast<Eigen::Index>(used.size()), 3);
  for (std::size_t v = 0; v < used.size(); ++v) {
    const auto it = position_of.find(used[v]);
    if (it == position_of.end()) throw Error(fmt::format("Gmsh returned no coordinates for node {}", used[v]), where);
    for (int i = 0; i < 3; ++i) mesh.vertices(static_cast<Eigen::Index>(v), i) = out.node_coords[3 * it->second + i];
  }
  mesh.validate(where);
  return mesh;
}

}  // namespace sinew
