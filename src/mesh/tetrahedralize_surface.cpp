#include "sinew/mesh/tetrahedralize_surface.hpp"

#include <gmsh.h>

#include <cmath>
#include <fmt/format.h>
#include <mutex>
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

VolumeMesh tetrahedralize_surface(const TriangleSurface& surface, double max_edge) {
  const std::string where = "tetrahedralize";
  if (!(max_edge > 0.0 && std::isfinite(max_edge)))
    throw Error(fmt::format("max_edge must be a positive finite number, got {}", max_edge), where);
  surface.validate(where, true);
  const SurfaceTopology topology = surface_topology(surface);
  if (!topology.watertight())
    throw Error(fmt::format("Gmsh needs a 2-manifold surface; this one has {} edges shared by more than two faces",
                            topology.nonmanifold_edges),
                where);
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
