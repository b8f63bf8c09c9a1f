#pragma once
// The per-frame output files of a run, whatever its integrator: the volume mesh with its fields
// (frame_NNNN.vtu, listed in simulation.pvd), the boundary surface (surface_NNNN.obj), the
// embedded render surface (embedded_surface_*, run/embedded_surface_output.hpp) and the
// obstacles and bones (run/shape_output.hpp), every `output.every` frames.
#include <filesystem>
#include <utility>
#include <vector>

#include "sinew/model/model.hpp"
#include "sinew/run/embedded_surface_output.hpp"
#include "sinew/run/shape_output.hpp"

namespace sinew {

class FrameOutput {
 public:
  // Writes nothing when `out` is empty.
  FrameOutput(const Scene& scene, const Model& model, std::filesystem::path out);

  void write(int frame, double time, const State& state);

  // simulation.pvd's (time, file) entries, kept in the checkpoint so a resumed run lists them all.
  const std::vector<std::pair<double, std::string>>& pvd() const { return pvd_; }
  void set_pvd(std::vector<std::pair<double, std::string>> entries) { pvd_ = std::move(entries); }

 private:
  const Scene& scene_;
  const Model& model_;
  std::filesystem::path out_;
  EmbeddedSurfaceOutput embedded_;
  ShapeOutput shapes_;
  std::vector<std::pair<double, std::string>> pvd_;
};

// Per-element fields of a state: the elastic energy (integrated), the volume-averaged energy
// density and J, and for a hyperelastic material the volume-averaged Frobenius norm of P.
struct ElementFields {
  Eigen::VectorXd energy, energy_density, J, stress_norm;
};
ElementFields element_fields(const Model& model, const Eigen::VectorXd& x);

}  // namespace sinew
