#include "gmsh_module_loader.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <mutex>
#include <string>
#include <vector>

#include "sinew/core/error.hpp"

namespace sinew {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRelativePath = "lib/sinew/gmsh_mesher.so";

std::vector<fs::path> candidates() {
  std::vector<fs::path> paths;
  // A packager's (or a test's) override: then only that path.
  if (const char* chosen = std::getenv("SINEW_GMSH_MODULE"); chosen != nullptr && *chosen != '\0') return {chosen};
  Dl_info info{};
  // The object holding this function: the sinew executable, a test, or the Python module.
  if (::dladdr(reinterpret_cast<void*>(&load_gmsh_module), &info) != 0 && info.dli_fname != nullptr) {
    std::error_code ec;
    const fs::path self = fs::canonical(info.dli_fname, ec);
    if (!ec) paths.push_back(self.parent_path() / kRelativePath);
  }
#ifdef SINEW_GMSH_MODULE_BUILT_AT
  paths.emplace_back(SINEW_GMSH_MODULE_BUILT_AT);
#endif
  return paths;
}

gmsh_module::TetrahedralizeFn load() {
  std::string tried;
  for (const fs::path& path : candidates()) {
    std::error_code ec;
    if (!fs::exists(path, ec)) {
      tried += fmt::format("{}{} (missing)", tried.empty() ? "" : ", ", path.string());
      continue;
    }
    // Never closed: Gmsh's static objects live until the process ends.
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    const char* why = handle ? nullptr : ::dlerror();
    if (handle) {
      if (void* entry = ::dlsym(handle, gmsh_module::kEntryPoint))
        return reinterpret_cast<gmsh_module::TetrahedralizeFn>(entry);
      why = "no entry point (a module from another Sinew version)";
    }
    tried += fmt::format("{}{} ({})", tried.empty() ? "" : ", ", path.string(), why ? why : "unknown error");
  }
  throw Error(fmt::format("cannot load Sinew's Gmsh module, which meshes surfaces into tetrahedra; tried {}. It is "
                          "built with Sinew as {} beside the sinew executable",
                          tried.empty() ? "nothing" : tried, kRelativePath),
              "tetrahedralize");
}

}  // namespace

gmsh_module::TetrahedralizeFn load_gmsh_module() {
  static std::mutex mutex;
  static gmsh_module::TetrahedralizeFn entry = nullptr;
  std::lock_guard lock(mutex);
  if (!entry) entry = load();  // a failure is retried next time (and reported again)
  return entry;
}

}  // namespace sinew
