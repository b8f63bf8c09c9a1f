#pragma once
// The surface parts of a scene (docs/scene-format.md, "Surfaces"): /mesh sources made from a
// closed triangle surface, and the embedded render surface written deformed every frame.
#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>

#include "sinew/element/embedding.hpp"
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

// The embedded surface of a scene: read once, bound to the simulation mesh at rest, written
// as embedded_surface_XXXX.obj and .ply (atomically) for the positions of a frame.
class EmbeddedSurfaceOutput {
 public:
  // Inactive (writes nothing) when the scene embeds no surface.
  EmbeddedSurfaceOutput(const Scene& scene, const VolumeMesh& mesh);
  bool active() const { return active_; }
  void write(const std::filesystem::path& out, int frame, const Eigen::VectorXd& x) const;
  const TriangleSurface& surface() const { return surface_; }
  const Embedding& embedding() const { return embedding_; }

 private:
  bool active_ = false;
  TriangleSurface surface_;
  Embedding embedding_;
};

}  // namespace sinew
