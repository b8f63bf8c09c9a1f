#pragma once
// The embedded render surface of a scene ("embed" in /mesh, docs/scene-format.md): read once,
// bound to the simulation mesh at rest, and written for every output frame as
//   embedded_surface_NNNN.obj  polygons, UVs, groups, objects, materials and smoothing groups as
//                              read, normals recomputed (io/obj_polygon_writer.hpp)
//   embedded_surface_NNNN.ply  the same polygons with per-vertex J and stress_norm
//   embedded_surface.pc2       one sample per output frame (Blender's Mesh Cache modifier)
//   embedded_surface_rest.obj  the rest surface the cache applies to (one object)
// plus copies of the OBJ's material libraries (docs/file-formats.md, "Render surfaces").
#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>

#include "sinew/element/discretization.hpp"
#include "sinew/element/embedding.hpp"
#include "sinew/io/point_cache.hpp"
#include "sinew/mesh/polygon_surface.hpp"
#include "sinew/model/scene.hpp"

namespace sinew {

// An OBJ through the polygon reader (everything kept); STL, PLY and OFF through the triangle
// reader (io/surface_reader.hpp), open surfaces allowed.
PolygonSurface read_render_surface(const std::filesystem::path& path);

class EmbeddedSurfaceOutput {
 public:
  // Inactive (writes nothing) when the scene embeds no surface. Errors name /mesh/embed.
  EmbeddedSurfaceOutput(const Scene& scene, const VolumeMesh& mesh);
  bool active() const { return active_; }

  // The files of output frame `frame` (a multiple of the scene's output.every) at mesh
  // positions x. `element_J` and `element_stress` (per element, optional) become per-vertex PLY
  // properties. Frame 0 starts the point cache, rest OBJ and material copies; the first frame
  // of a resumed run cuts the cache back to the frames before it.
  void write(const std::filesystem::path& out, int frame, const Eigen::VectorXd& x, const Discretization& disc,
             const Eigen::VectorXd* element_J = nullptr, const Eigen::VectorXd* element_stress = nullptr);

  const PolygonSurface& surface() const { return surface_; }
  const Embedding& embedding() const { return embedding_; }

 private:
  bool active_ = false;
  std::filesystem::path source_;
  int every_ = 1;
  PolygonSurface surface_;
  Embedding embedding_;
  std::vector<int> cached_;  // surface positions in the point cache (those a face uses)
  std::optional<Pc2Appender> cache_;
};

}  // namespace sinew
