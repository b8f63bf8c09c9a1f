#pragma once
// The per-frame output files of a run, whatever its integrator: the volume mesh with its fields
// (frame_NNNN.vtu, listed in simulation.pvd, which is rewritten only by write_collection: the
// list grows with the frames, so writing it every frame would cost the run O(frames^2)), the boundary surface (surface_NNNN.obj), the
// embedded render surface (embedded_surface_*, run/embedded_surface_output.hpp) and the
// obstacles and bones (run/shape_output.hpp), every `output.every` frames.
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "sinew/io/vtk_writer.hpp"
#include "sinew/model/model.hpp"
#include "sinew/run/embedded_surface_output.hpp"
#include "sinew/run/shape_output.hpp"

namespace sinew {

class FrameOutput {
 public:
  // Writes nothing when `out` is empty.
  FrameOutput(const Scene& scene, const Model& model, std::filesystem::path out);

  void write(int frame, double time, const State& state);

  // Writes simulation.pvd, listing every .vtu written so far, if that list changed since it was
  // last written (the run calls it at each checkpoint and at its end).
  void write_collection();

  // A run resumed after `last_frame`: simulation.pvd lists the frames 0..last_frame the scene's
  // output settings wrote, at time_of(frame), before the frames to come.
  void resume_after(int last_frame, const std::function<double(int)>& time_of);

 private:
  const Scene& scene_;
  const Model& model_;
  std::filesystem::path out_;
  EmbeddedSurfaceOutput embedded_;
  ShapeOutput shapes_;
  std::vector<std::pair<double, std::string>> pvd_;
  bool pvd_changed_ = false;
};

// Per-element fields of a state: the elastic energy (integrated), the volume-averaged energy
// density and J, and for a hyperelastic material the volume-averaged Frobenius norm of P.
struct ElementFields {
  Eigen::VectorXd energy, energy_density, J, stress_norm;
};
ElementFields element_fields(const Model& model, const Eigen::VectorXd& x);

// Appends the continuum fields (element/continuum_fields.hpp) per element and per vertex:
// J (per vertex; per element it is a cell scalar already), principal_stretches,
// green_lagrange_strain and, for a hyperelastic material, cauchy_stress and von_mises.
void add_continuum_fields(const Model& model, const Eigen::VectorXd& x, VtuFields& fields);

}  // namespace sinew
