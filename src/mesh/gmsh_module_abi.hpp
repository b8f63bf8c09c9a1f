#pragma once
// What the library and the Gmsh module (gmsh_module.cpp, built as <build>/lib/sinew/gmsh_mesher.so
// and loaded by gmsh_module_loader.cpp on first use) pass each other. Gmsh pulls in ~90 shared
// libraries (OpenCASCADE, FLTK, ...) whose ~100,000 relocations cost every `sinew` start-up
// about half a second; only the surface tetrahedraliser needs them, so they load with it.
// Both sides are built from this tree by the same compiler, so the ABI is plain C++ behind one
// extern "C" symbol; no exception crosses it (the module reports an error as text).
#include <cstddef>
#include <string>
#include <vector>

namespace sinew::gmsh_module {

struct Input {
  std::vector<double> coords;          // x, y, z per surface vertex; vertex v is Gmsh node v + 1
  std::vector<std::size_t> triangles;  // three 1-based node tags per outward triangle
  double max_edge = 0.0;               // Mesh.MeshSizeMax
};

struct Output {
  std::vector<std::size_t> node_tags;  // every node of the mesh
  std::vector<double> node_coords;     // x, y, z per node tag, in node_tags' order
  std::vector<std::size_t> tet_nodes;  // four node tags per tetrahedron
  std::string error;                   // non-empty: Gmsh failed, and why
};

// The module's entry point; versioned so that a stale module is refused instead of misread.
using TetrahedralizeFn = void (*)(const Input&, Output&);
inline constexpr const char* kEntryPoint = "sinew_gmsh_tetrahedralize_v1";

}  // namespace sinew::gmsh_module
