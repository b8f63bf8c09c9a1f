#pragma once
// The surface parts of a scene (docs/scene-format.md, "Surfaces"): /mesh sources made from a
// closed triangle surface, and the embedded render surface (run/embedded_surface_output.hpp).
#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>

#include "sinew/mesh/triangle_surface.hpp"
#include "sinew/model/scene.hpp"

namespace sinew {

class JsonObject;

// Reads the surface keys of /mesh ("surface", "tetrahedralize", "non_manifold", "max_edge",
// "embed") into `spec` when `o` names a surface source, and returns whether it did.
bool parse_surface_mesh(JsonObject& o, const std::filesystem::path& folder, MeshSpec& spec);

// "embed": true (the source's own surface, `own_surface`), false, or a surface file resolved
// against `folder`; nullopt when absent or false.
std::optional<std::filesystem::path> parse_embedded_surface(JsonObject& o, const std::filesystem::path& folder,
                                                            const std::optional<std::filesystem::path>& own_surface);

// The volume mesh of a surface source (not validated here); nullopt for other sources.
std::optional<VolumeMesh> build_surface_mesh(const MeshSpec& spec);


}  // namespace sinew
