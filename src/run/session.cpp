#include "sinew/run/session.hpp"

#include <fmt/format.h>

#include "sinew/core/error.hpp"
#include "sinew/forms/external_force_form.hpp"
#include "sinew/io/atomic_file.hpp"
#include "sinew/run/frame_output.hpp"
#include "sinew/run/run_summary.hpp"

namespace sinew {

Session::Session(Scene scene, std::filesystem::path out_dir, bool strict)
    : scene_(std::move(scene)), model_(build_model(scene_)), out_(std::move(out_dir)) {
  if (strict && !model_.warnings.empty())  // as run_scene
    throw Error(model_.warnings.front() + " (a warning, an error with --strict)");
  state_ = model_.initial;
  const Discretization& disc = *model_.disc;
  summary_.vertices = disc.mesh().num_vertices();
  summary_.elements = disc.num_elements();
  for (Eigen::Index e = 0; e < disc.num_elements(); ++e) summary_.rest_volume += disc.rest_volume(e);
  summary_.external_force = model_.external_forces.reshaped(3, model_.external_forces.size() / 3).rowwise().sum();
  summary_.warnings = model_.warnings;
  summary_.x = state_.x;
  output_ = std::make_unique<FrameOutput>(scene_, model_, out_);
  if (!out_.empty()) {
    remove_previous_outputs(out_);
    ensure_directory(out_);
    output_->write(0, 0.0, state_);
    output_->write_collection();
  }
}

Session::~Session() = default;

double Session::time() const {
  return model_.integrator->dynamic() ? frame_ * model_.integrator->frame_duration() : double(frame_);
}

const FrameRecord& Session::step(const IterationProgress& progress) {
  summary_.frames.push_back(simulate_frame(model_, state_, frame_ + 1, progress));
  ++frame_;  // only now: an exception (Ctrl-C in a progress callback) leaves the frame count
  summary_.x = state_.x;
  const FrameRecord& record = summary_.frames.back();
  if (!out_.empty()) {
    output_->write(frame_, record.time, state_);
    output_->write_collection();  // a stepped session may stop at any frame: the .pvd stays current
    write_summary(out_, scene_, model_, summary_, frame_);
  }
  return record;
}

const KinematicCondition& Session::condition(size_t index) const {
  if (index >= model_.kinematics->size())
    throw Error(fmt::format("no boundary condition {} (the scene has {})", index, model_.kinematics->size()), "boundary");
  return (*model_.kinematics)[index];
}

void Session::set_boundary_motion(size_t index, RigidMotion motion) {
  const std::string where = condition(index).source;
  // A displacement written without an amplitude ramps to the scene's last frame, as in the scene.
  if (auto* d = std::get_if<Displacement>(&motion)) d->amplitude.resolve_ramp(scene_.frames);
  validate_motion(motion, where);
  (*model_.kinematics)[index].motion = std::move(motion);
}

RigidTransform Session::boundary_transform(size_t index, double frame) const {
  return transform_at(condition(index).motion, frame);
}

void Session::move_boundary(size_t index, const RigidTransform& target) {
  const std::string where = condition(index).source;
  if (!target.R.allFinite() || !target.t.allFinite()) throw Error("the target transform must be finite", where);
  if ((target.R.transpose() * target.R - Mat3::Identity()).norm() > 1e-9 || target.R.determinant() <= 0.0)
    throw Error("the target rotation must be a rotation matrix (orthonormal, determinant 1)", where);
  const RigidTransform now = boundary_transform(index, frame_);
  Keyframes keys;
  keys.keys.push_back({double(frame_), Eigen::Quaterniond(now.R), now.t});
  keys.keys.push_back({double(frame_ + 1), Eigen::Quaterniond(target.R), target.t});
  set_boundary_motion(index, std::move(keys));
}

Eigen::VectorXd Session::external_forces() const { return model_.external_forces_at(frame_); }

void Session::set_external_forces(const Eigen::VectorXd& forces) {
  if (forces.size() != model_.external_forces.size())
    throw Error(fmt::format("need {} values (3 per vertex), got {}", model_.external_forces.size(), forces.size()),
                "external forces");
  if (!forces.allFinite()) throw Error("must be finite", "external forces");
  // One constant load replaces the scene's loads and their amplitudes. The prescribed motion sets
  // the load form from the shared loads at every solve; a scene without loads had no load form,
  // so one is added (its forces then stay as set here).
  *model_.loads = {ScaledLoad{forces, Amplitude::constant()}};
  model_.external_forces = forces;
  summary_.external_force = forces.reshaped(3, forces.size() / 3).rowwise().sum();
  if (!model_.load_form) {
    model_.load_form = std::make_shared<ExternalForceForm>(forces);
    model_.problem->add_form(model_.load_form);
  }
  model_.load_form->forces() = forces;
}

}  // namespace sinew
