// The Gmsh module: the only code that calls Gmsh, built as a shared object of its own
// (gmsh_module_abi.hpp says why) and not part of libsinew.
#include <gmsh.h>

#include <exception>
#include <string>

#include "gmsh_module_abi.hpp"

namespace {

constexpr int kGmshTriangle = 2;  // Gmsh element type numbers
constexpr int kGmshTetrahedron = 4;

// Gmsh keeps one global model; it is finalised on every exit path (the caller serialises calls).
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

void tetrahedralize(const sinew::gmsh_module::Input& in, sinew::gmsh_module::Output& out) {
  GmshSession session;
  gmsh::model::add("sinew");
  const int s = gmsh::model::addDiscreteEntity(2);
  std::vector<std::size_t> tags(in.coords.size() / 3);
  for (std::size_t v = 0; v < tags.size(); ++v) tags[v] = v + 1;
  gmsh::model::mesh::addNodes(2, s, tags, in.coords);
  gmsh::model::mesh::addElementsByType(s, kGmshTriangle, {}, in.triangles);
  // The discrete surface closes the volume as it is: no reparametrisation (which fails for
  // surfaces without boundary curves, such as a sphere), so the input triangles stay.
  const int loop = gmsh::model::geo::addSurfaceLoop({s});
  gmsh::model::geo::addVolume({loop});
  gmsh::model::geo::synchronize();
  gmsh::option::setNumber("Mesh.MeshSizeMax", in.max_edge);
  gmsh::model::mesh::generate(3);
  std::vector<double> parametric;
  gmsh::model::mesh::getNodes(out.node_tags, out.node_coords, parametric, -1, -1, true, false);
  std::vector<std::size_t> element_tags;
  gmsh::model::mesh::getElementsByType(kGmshTetrahedron, element_tags, out.tet_nodes);
}

}  // namespace

extern "C" __attribute__((visibility("default"))) void sinew_gmsh_tetrahedralize_v1(
    const sinew::gmsh_module::Input& in, sinew::gmsh_module::Output& out) noexcept {
  try {
    tetrahedralize(in, out);
  } catch (const std::string& message) {  // how the Gmsh API reports its errors
    out.error = message.empty() ? "unknown error" : message;
  } catch (const std::exception& e) {
    out.error = e.what();
  } catch (...) {
    out.error = "unknown error";
  }
}
