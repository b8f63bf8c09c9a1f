#pragma once
// The browser viewer of a scene's run (io/viewer_writer.hpp): the deformed boundary surface
// coloured by per-vertex J and von Mises stress, the embedded render surface (same fields,
// interpolated), and every obstacle and bone at its pose of the frame.
//
// The run loop feeds it x after each written frame and calls finish() at the end; it does
// not touch the solver. `sinew viewer` builds the same viewer afterwards from a run's .vtu
// frames (read_run_frames below).
#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sinew/element/discretization.hpp"
#include "sinew/element/embedding.hpp"
#include "sinew/io/viewer_writer.hpp"
#include "sinew/material/material.hpp"
#include "sinew/mesh/surface.hpp"
#include "sinew/model/scene.hpp"

namespace sinew {

// Per-element mean over quadrature points of J = det F and the von Mises stress of the Cauchy
// stress sigma = P F^T / J (Pa for a material in Pa). An element whose F leaves the material's
// domain (inverted) gets a non-finite von Mises value.
struct ElementStressFields {
  Eigen::VectorXd J, von_mises;
};
ElementStressFields element_stress_fields(const Discretization& disc, const Material& material, const Eigen::VectorXd& x);

class RunViewer {
 public:
  // Reads the embedded render surface when the scene has one (a sinew::Error names it if it
  // cannot be read). `material` evaluates the stresses.
  RunViewer(const Scene& scene, std::shared_ptr<const Discretization> disc, std::shared_ptr<const Material> material,
            ViewerOptions options = {});

  // Frame `frame` at positions x (x[3 v + i]) and `time`: seconds for dynamic runs, the frame
  // number for quasistatic ones (as in simulation.pvd); times must increase.
  void add_frame(int frame, double time, const Eigen::VectorXd& x);
  std::size_t frames() const { return writer_->frames(); }
  // Writes `html` (conventionally OUT/viewer.html) and the .glb beside it.
  void finish(const std::filesystem::path& html) const { writer_->finish(html); }
  const ViewerWriter& writer() const { return *writer_; }

 private:
  const Scene* scene_;
  std::shared_ptr<const Discretization> disc_;
  std::shared_ptr<const Material> material_;
  BoundarySurface surface_;
  std::optional<Embedding> embedding_;
  struct Rigid {  // an obstacle or bone: its rest mesh and the pose of a frame
    Eigen::MatrixX3d rest;
    std::size_t index;  // into scene.obstacles or scene.rig->bones
    bool bone;
  };
  std::vector<Rigid> rigid_;
  std::unique_ptr<ViewerWriter> writer_;
};

// A frame a run wrote: its number, time and positions.
struct RunFrame {
  int frame = 0;
  double time = 0.0;
  Eigen::VectorXd x;
};
// The frames listed in OUT/simulation.pvd, read back from their .vtu files, in time order.
// Throws a sinew::Error naming the file when the collection is missing or empty, a frame file
// cannot be read, or its vertex count is not `vertices`.
std::vector<RunFrame> read_run_frames(const std::filesystem::path& out, Eigen::Index vertices);

// Builds the viewer of a finished run from its output folder: the scene rebuilt (mesh and
// material), the frames read back, OUT/viewer.html and OUT/viewer.glb written. Returns the
// number of frames.
std::size_t write_run_viewer(const Scene& scene, const std::filesystem::path& out, ViewerOptions options = {});

}  // namespace sinew
