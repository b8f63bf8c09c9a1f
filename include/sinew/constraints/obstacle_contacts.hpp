#pragma once
// Constraint contact (paper 001 §5) against the scene's rigid obstacles (contact/obstacle.hpp):
// plane, sphere, capsule, cylinder and box, static or on a rigid path. Each listed vertex closer
// than `margin` to an obstacle, at that obstacle's pose at the step's end, becomes one
// ContactCandidate per obstacle, with the obstacle's outward normal, signed distance, friction
// coefficient and the velocity of the obstacle point under the vertex over the step (so
// friction holds the vertex to a moving obstacle, not to the world).
#include <memory>
#include <vector>

#include "sinew/constraints/contact_constraints.hpp"
#include "sinew/motion/obstacle.hpp"

namespace sinew {

struct ObstacleContact {
  std::shared_ptr<const Obstacle> obstacle;
  double friction = 0.0;  // Coulomb coefficient mu
};

// `vertices`: the candidates (typically the boundary vertices); `seconds_per_frame` converts the
// stepper's time to the obstacles' frame numbers.
ContactProvider obstacle_contacts(std::vector<ObstacleContact> obstacles, std::vector<int> vertices, double margin,
                                  double seconds_per_frame);

}  // namespace sinew
