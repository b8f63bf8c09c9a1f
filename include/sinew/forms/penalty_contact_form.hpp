#pragma once
// Penalty contact of the boundary vertices against rigid obstacles, as one energy term that
// Newton minimises together with the others:
//   E = sum_(v,o) a_v k_o / 2 max(0, -d_o(x_v))^2                       (C1 penetration penalty)
//     + sum_(v,o) mu_o lambda_vo f0(|T_vo (x_v - x_v^n - dobs_vo)|)      (smoothed Coulomb friction)
// a_v is the vertex's share of the rest boundary area (so k is a pressure per unit depth), the
// obstacles are placed at the step's end time. Friction is lagged as in IPC (Li et al. 2020,
// §5): the normal force lambda, the tangent projector T = I - n n^T and the obstacle's own motion
// dobs at the contact point are frozen at the step's start, and f0 is IPC's C1 mollifier of |u|
// with slip threshold eps (f0(s) = s beyond eps), so sticking is a stiff spring below eps.
#include <memory>
#include <vector>

#include "sinew/motion/obstacle.hpp"
#include "sinew/forms/form.hpp"
#include "sinew/mesh/surface.hpp"

namespace sinew {

struct ContactParameters {
  double stiffness = 0.0;  // k: penalty pressure per unit penetration depth (Pa/m)
  double friction = 0.0;   // mu: Coulomb coefficient
};

// Each boundary vertex's share of the rest boundary area (a third of each triangle it corners).
Eigen::VectorXd boundary_vertex_areas(const VolumeMesh& mesh, const BoundarySurface& surface);

struct ContactStats {
  int contacts = 0;             // (vertex, obstacle) pairs with penetration
  double max_penetration = 0.0;  // deepest, >= 0
  double penalty_energy = 0.0;   // the conservative (penetration) part of the energy
};

class PenaltyContactForm final : public Form {
 public:
  // `vertices`: the vertices that can touch (the boundary), `areas` one per vertex of the mesh.
  PenaltyContactForm(std::vector<std::shared_ptr<const Obstacle>> obstacles, std::vector<ContactParameters> parameters,
                     std::vector<int> vertices, Eigen::VectorXd areas, bool project_hessian = true);

  std::string name() const override { return "contact"; }

  // Starts a step from x_n at frame0 towards frame1 (obstacles placed at frame1), freezing the
  // friction data; slip_epsilon is the tangential displacement over the step below which
  // contact sticks (IPC's eps_v * h).
  void begin_step(const Eigen::VectorXd& x_n, double frame0, double frame1, double slip_epsilon);

  double value(const Eigen::VectorXd& x) const override;
  void add_gradient(const Eigen::VectorXd& x, Eigen::VectorXd& g) const override;
  void add_hessian(const Eigen::VectorXd& x, BlockHessian& H) const override;

  ContactStats stats(const Eigen::VectorXd& x) const;
  const std::vector<std::shared_ptr<const Obstacle>>& obstacles() const { return obstacles_; }
  double frame() const { return frame_; }

 private:
  struct FrictionPair {
    int vertex = 0;
    int obstacle = 0;
    double normal_force = 0.0;  // lambda = a k max(0, -d) at the step's start
    Mat3 tangent = Mat3::Identity();  // I - n n^T
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // x_n + dobs: the sticking position
  };
  std::vector<std::shared_ptr<const Obstacle>> obstacles_;
  std::vector<ContactParameters> params_;
  std::vector<int> vertices_;
  Eigen::VectorXd areas_;
  bool project_;
  double frame_ = 0.0;
  double epsilon_ = 1e-3;
  std::vector<FrictionPair> friction_;
};

}  // namespace sinew
