#pragma once
// A scene advanced one frame at a time by its caller (the Python module's Simulation): between
// frames the caller reads the state, changes a boundary condition's motion or the external forces,
// and advances again. Each frame is simulate_frame's (simulation.hpp), as in run_scene.
#include <filesystem>
#include <memory>
#include <vector>

#include "sinew/model/model.hpp"
#include "sinew/run/simulation.hpp"

namespace sinew {

class FrameOutput;

class Session {
 public:
  // Builds and validates the model (every input problem is a sinew::Error here). With `out_dir`,
  // an earlier run's files there are replaced and each frame's outputs (frame_output.hpp, frame 0
  // at once) and summary.json are written as in run_scene; there is no checkpoint, since the
  // motions may have been changed by the caller. The model's warnings are in summary().warnings;
  // `strict` makes the first one an error, as run_scene's option does.
  explicit Session(Scene scene, std::filesystem::path out_dir = {}, bool strict = false);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  const Scene& scene() const { return scene_; }
  const Model& model() const { return model_; }
  const State& state() const { return state_; }
  int frame() const { return frame_; }  // frames advanced so far
  double time() const;                  // simulated seconds (dynamics) or the frame number
  const RunSummary& summary() const { return summary_; }

  // Advances one frame and returns its record (also appended to summary().frames). A frame that
  // did not converge keeps the state its last attempt reached; stepping on is the caller's choice.
  const FrameRecord& step(const IterationProgress& progress = {});

  // Boundary condition `index` (scene order) follows `motion` from the next frame on; motions are
  // functions of the frame number, relative to the rest pose (docs/scene-format.md). Only the
  // components the condition prescribes move (a roller's own stay free).
  void set_boundary_motion(size_t index, RigidMotion motion);
  // Boundary condition `index` reaches `target` (relative to its rest pose) at the end of the next
  // frame, from where it is now (a keyframed motion), and holds it afterwards.
  void move_boundary(size_t index, const RigidTransform& target);
  // Where boundary condition `index` puts its vertices at a frame number (relative to the rest pose).
  RigidTransform boundary_transform(size_t index, double frame) const;

  // The external nodal forces (x[3 v + i] layout) at the current frame: gravity, point loads and
  // tractions at their amplitudes as the scene gave them, or what set_external_forces set.
  Eigen::VectorXd external_forces() const;
  // Constant forces that replace the scene's loads (and their amplitudes) from the next frame on.
  void set_external_forces(const Eigen::VectorXd& forces);

 private:
  const KinematicCondition& condition(size_t index) const;
  Scene scene_;
  Model model_;
  State state_;
  int frame_ = 0;
  RunSummary summary_;
  std::filesystem::path out_;
  std::unique_ptr<FrameOutput> output_;
};

}  // namespace sinew
