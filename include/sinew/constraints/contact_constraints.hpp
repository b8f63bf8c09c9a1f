#pragma once
// Contact candidates for constraint contact (paper 001 §5): whatever detects collisions hands
// the stepper a list of vertex contacts; the stepper linearises gap(x + dx) = gap + n . dx_v.
#include <Eigen/Core>
#include <functional>
#include <vector>

namespace sinew {

struct ContactCandidate {
  int vertex = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, pointing out of the obstacle
  double gap = 0.0;                                   // signed distance, negative = penetrating
  double friction = 0.0;                              // Coulomb coefficient mu
  Eigen::Vector3d obstacle_velocity = Eigen::Vector3d::Zero();  // for the relative sliding velocity
};

// Candidates at positions x (x[3 v + i]) at the end of the step [step_start, step_end]
// (seconds since the simulation started): moving obstacles are placed at step_end, and their
// velocity over the step goes into the friction rows.
using ContactProvider =
    std::function<std::vector<ContactCandidate>(const Eigen::VectorXd& x, double step_start, double step_end)>;

// A static infinite ground plane {p : normal . p = offset}: every vertex closer than `margin`
// (or penetrating) is a candidate. For experiments; general obstacles come from elsewhere.
ContactProvider ground_plane_contacts(const Eigen::Vector3d& normal, double offset, double friction,
                                      double margin);

}  // namespace sinew
