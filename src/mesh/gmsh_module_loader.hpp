#pragma once
// Finds and loads the Gmsh module (gmsh_module_abi.hpp) the first time a surface is
// tetrahedralised; later calls reuse it.
#include "gmsh_module_abi.hpp"

namespace sinew {

// The module's entry point. Loads the file the environment variable SINEW_GMSH_MODULE names if
// set, else looks for lib/sinew/gmsh_mesher.so beside the executable (or the shared object, such
// as the Python module) that holds this code, then in the build tree it was built in. Throws a sinew::Error naming the paths tried and the loader's reason when none loads.
gmsh_module::TetrahedralizeFn load_gmsh_module();

}  // namespace sinew
