#include "sinew/mesh/tetrahedralize_surface.hpp"

#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <mutex>
#include <queue>
#include <unordered_map>
#include <vector>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

constexpr int kGmshTriangle = 2;     // Gmsh element type numbers
constexpr int kGmshTetrahedron = 4;

// Gmsh keeps one global model: calls are serialised and the library is finalised on every
// exit path.
std::mutex gmsh_mutex;
struct GmshSession {
  GmshSession() {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 0);
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

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
  std::lock_guard lock(gmsh_mutex);
  VolumeMesh mesh;
  mesh.kind = ElementKind::Tet4;
  try {
    GmshSession session;
    gmsh::model::add("sinew");
    const int s = gmsh::model::addDiscreteEntity(2);
    std::vector<std::size_t> tags(static_cast<size_t>(surface.num_vertices()));
    std::vector<double> coords;
    coords.reserve(3 * tags.size());
    for (Eigen::Index v = 0; v < surface.num_vertices(); ++v) {
      tags[static_cast<size_t>(v)] = static_cast<std::size_t>(v + 1);
      for (int i = 0; i < 3; ++i) coords.push_back(surface.vertices(v, i));
    }
    gmsh::model::mesh::addNodes(2, s, tags, coords);
    std::vector<std::size_t> triangles;
    for (Eigen::Index f = 0; f < surface.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) triangles.push_back(static_cast<std::size_t>(surface.faces(f, k) + 1));
    gmsh::model::mesh::addElementsByType(s, kGmshTriangle, {}, triangles);
    // The discrete surface closes the volume as it is: no reparametrisation (which fails for
    // surfaces without boundary curves, such as a sphere), so the input triangles stay.
    const int loop = gmsh::model::geo::addSurfaceLoop({s});
    gmsh::model::geo::addVolume({loop});
    gmsh::model::geo::synchronize();
    gmsh::option::setNumber("Mesh.MeshSizeMax", max_edge);
    gmsh::model::mesh::generate(3);

    std::vector<std::size_t> node_tags;
    std::vector<double> node_coords, parametric;
    gmsh::model::mesh::getNodes(node_tags, node_coords, parametric, -1, -1, true, false);
    std::vector<std::size_t> element_tags, element_nodes;
    gmsh::model::mesh::getElementsByType(kGmshTetrahedron, element_tags, element_nodes);
    if (element_tags.empty()) throw Error("Gmsh produced no tetrahedra", where);
    // Only the nodes tetrahedra use, numbered in first-use order.
    std::unordered_map<std::size_t, std::size_t> position_of;
    for (std::size_t i = 0; i < node_tags.size(); ++i) position_of[node_tags[i]] = i;
    std::unordered_map<std::size_t, int> index_of;
    std::vector<std::size_t> used;
    mesh.elements.resize(static_cast<Eigen::Index>(element_tags.size()), 4);
    for (std::size_t e = 0; e < element_tags.size(); ++e)
      for (int a = 0; a < 4; ++a) {
        const std::size_t tag = element_nodes[4 * e + a];
        auto [it, fresh] = index_of.try_emplace(tag, static_cast<int>(used.size()));
        if (fresh) used.push_back(tag);
        mesh.elements(static_cast<Eigen::Index>(e), a) = it->second;
      }
    mesh.vertices.resize(static_cast<Eigen::Index>(used.size()), 3);
    for (std::size_t v = 0; v < used.size(); ++v) {
      const auto it = position_of.find(used[v]);
      if (it == position_of.end()) throw Error(fmt::format("Gmsh returned no coordinates for node {}", used[v]), where);
      for (int i = 0; i < 3; ++i) mesh.vertices(static_cast<Eigen::Index>(v), i) = node_coords[3 * it->second + i];
    }
  } catch (const Error&) {
    throw;
  } catch (const std::string& message) {  // how the Gmsh API reports its errors
    throw Error(fmt::format("Gmsh failed: {}", message), where);
  } catch (const std::exception& e) {
    throw Error(fmt::format("Gmsh failed: {}", e.what()), where);
  } catch (...) {
    throw Error("Gmsh failed", where);
  }
  mesh.validate(where);
  return mesh;
}

}  // namespace sinew
