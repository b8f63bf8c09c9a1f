#include "sinew/constraints/obstacle_contacts.hpp"

#include "sinew/core/error.hpp"

namespace sinew {

ContactProvider obstacle_contacts(std::vector<ObstacleContact> obstacles, std::vector<int> vertices, double margin,
                                  double seconds_per_frame) {
  if (!(seconds_per_frame > 0.0)) throw Error("seconds per frame must be positive", "obstacle contacts");
  if (!(margin >= 0.0)) throw Error("contact margin must be non-negative", "obstacle contacts");
  for (const ObstacleContact& o : obstacles)
    if (!o.obstacle || !(o.friction >= 0.0)) throw Error("needs an obstacle and a friction coefficient >= 0", "obstacle contacts");
  return [obstacles = std::move(obstacles), vertices = std::move(vertices), margin, seconds_per_frame](
             const Eigen::VectorXd& x, double step_start, double step_end) {
    const double frame0 = step_start / seconds_per_frame, frame1 = step_end / seconds_per_frame;
    const double h = step_end - step_start;
    std::vector<ContactCandidate> out;
    for (const ObstacleContact& o : obstacles)
      for (int v : vertices) {
        const SurfaceQuery q = o.obstacle->query(x.segment<3>(3 * static_cast<Eigen::Index>(v)), frame1);
        if (q.distance >= margin) continue;
        ContactCandidate c{v, q.normal, q.distance, o.friction, Eigen::Vector3d::Zero()};
        // The obstacle point now under the vertex was elsewhere at the step's start: its mean
        // velocity over the step is what backward Euler's v_{n+1} must match to stick.
        if (o.obstacle->moves() && h > 0.0) c.obstacle_velocity = -o.obstacle->displacement(q.closest, frame1, frame0) / h;
        out.push_back(c);
      }
    return out;
  };
}

}  // namespace sinew
