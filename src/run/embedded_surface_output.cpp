#include "sinew/run/embedded_surface_output.hpp"

#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/element/nodal_fields.hpp"
#include "sinew/io/obj_polygon_reader.hpp"
#include "sinew/io/obj_polygon_writer.hpp"
#include "sinew/io/ply_writer.hpp"
#include "sinew/io/surface_reader.hpp"

namespace sinew {

PolygonSurface read_render_surface(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".obj") return read_obj_polygon_surface(path);
  const TriangleSurface t = read_triangle_surface(path, /*require_closed=*/false);
  PolygonSurface s;
  s.positions = t.vertices;
  for (Eigen::Index f = 0; f < t.faces.rows(); ++f) s.add_face({{t.faces(f, 0)}, {t.faces(f, 1)}, {t.faces(f, 2)}});
  return s;
}

EmbeddedSurfaceOutput::EmbeddedSurfaceOutput(const Scene& scene, const VolumeMesh& mesh) {
  if (!scene.mesh.embed) return;
  try {
    source_ = *scene.mesh.embed;
    surface_ = read_render_surface(source_);
    surface_.validate(source_.string());
    embedding_ = embed_points(mesh, surface_.positions);
  } catch (const Error& e) {
    throw e.within(scene.file.string() + ": /mesh/embed");
  }
  // Blender's OBJ importer drops vertices no face uses; the cache must match what it builds.
  std::vector<char> unused(static_cast<size_t>(surface_.num_positions()), 0);
  for (int v : surface_.unused_positions()) unused[static_cast<size_t>(v)] = 1;
  for (Eigen::Index v = 0; v < surface_.num_positions(); ++v)
    if (!unused[static_cast<size_t>(v)]) cached_.push_back(static_cast<int>(v));
  every_ = scene.output.every;
  active_ = true;
}

void EmbeddedSurfaceOutput::write(const std::filesystem::path& out, int frame, const Eigen::VectorXd& x,
                                  const Discretization& disc, const Eigen::VectorXd* element_J,
                                  const Eigen::VectorXd* element_stress) {
  if (!active_) return;
  const Eigen::MatrixX3d deformed = embedding_.positions(x);
  Eigen::MatrixX3d cached(static_cast<Eigen::Index>(cached_.size()), 3);
  for (size_t i = 0; i < cached_.size(); ++i) cached.row(static_cast<Eigen::Index>(i)) = deformed.row(cached_[i]);
  const std::filesystem::path pc2 = out / "embedded_surface.pc2";
  if (frame == 0) {
    copy_material_libraries(surface_, source_, out);
    ObjWriteOptions rest_options;
    rest_options.objects = false;  // one Blender object for the Mesh Cache modifier
    const PolygonSurface rest = keep_positions(surface_, cached_);
    write_obj_polygon_surface(out / "embedded_surface_rest.obj", rest, rest.positions, rest_options);
    cache_.emplace(pc2, static_cast<Eigen::Index>(cached_.size()), 0.0f, static_cast<float>(every_));
  } else if (!cache_) {  // a resumed run: keep the samples of frames 0, every, ..., frame - every
    cache_.emplace(Pc2Appender::resume(pc2, static_cast<Eigen::Index>(cached_.size()), frame / every_));
  }
  cache_->append(cached);
  write_obj_polygon_surface(out / fmt::format("embedded_surface_{:04d}.obj", frame), surface_, deformed);
  PlyVertexScalars scalars;
  if (element_J) scalars.emplace_back("J", interpolate_at_points(embedding_, nodal_average(disc, *element_J)));
  if (element_stress)
    scalars.emplace_back("stress_norm", interpolate_at_points(embedding_, nodal_average(disc, *element_stress)));
  write_ply(out / fmt::format("embedded_surface_{:04d}.ply", frame), surface_, deformed, scalars);
}

}  // namespace sinew
