#pragma once
// A scene turned into a model: the mesh and its discretisation, the forms of the total energy,
// the prescribed motion, and the integrator that advances it. Everything a run needs, built and
// validated before anything is written; also what `sinew check` inspects.
#include <memory>
#include <optional>
#include <vector>

#include "sinew/assembly/problem.hpp"
#include "sinew/constraints/energy_limit.hpp"
#include "sinew/element/discretization.hpp"
#include "sinew/forms/elastic_form.hpp"
#include "sinew/forms/external_force_form.hpp"
#include "sinew/forms/inertia_form.hpp"
#include "sinew/forms/penalty_contact_form.hpp"
#include "sinew/integrator/integrator.hpp"
#include "sinew/mesh/surface.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/model/scene_rig.hpp"

namespace sinew {

// A vertex whose DOFs are in a rotated frame (Problem::set_vertex_frames) and the number of its
// first local DOFs that are prescribed.
struct VertexFrameDofs {
  int vertex = 0;
  int count = 0;
};

// A load's nodal forces at amplitude 1 and its amplitude over the frames.
struct ScaledLoad {
  Eigen::VectorXd forces;
  Amplitude amplitude;
};

struct Model {
  std::shared_ptr<Discretization> disc;
  BuiltMaterial material;
  // The elastic energy: the scene's material (ElasticForm) or, for the energy-limited
  // "corotational" model, corotational hexahedra. `hyperelastic` is set when it is the former.
  std::shared_ptr<ElementForm> elastic;
  std::shared_ptr<ElasticForm> hyperelastic;
  // The total energy the integrator works on: elastic, loads, bone springs, self-contact and, by
  // integrator, penalty contact, inertia and damping (the energy-limited integrator: the potential
  // energy only; its inertia, obstacles and limits are the stepper's).
  std::shared_ptr<Problem> problem;
  BoundarySurface surface;
  // External loads (gravity, point loads, tractions) as nodal forces, each with its amplitude;
  // the integrator sets `load_form` to their sum at each (fractional) frame it solves.
  std::vector<ScaledLoad> loads;
  std::shared_ptr<ExternalForceForm> load_form;
  Eigen::VectorXd external_forces;  // the loads at full amplitude (frame 1 of constant loads)
  Eigen::VectorXd external_forces_at(double frame) const;
  std::vector<KinematicCondition> kinematics;  // the scene's boundary conditions, in order
  // Per global DOF of a vertex without a rotated frame: the boundary entry prescribing it, or -1.
  std::vector<int> dof_owner;
  // Vertices with a rotated frame (a direction that is not a coordinate axis): how many of their
  // local DOFs are prescribed, and each prescribed direction with its boundary entry.
  std::vector<VertexFrameDofs> vertex_frames;
  struct VertexDirection {
    int vertex, condition;
    Eigen::Vector3d direction;
  };
  std::vector<VertexDirection> vertex_directions;
  std::vector<std::string> warnings;  // suspicious but legal input (a selector taking every vertex, ...)
  SceneRig rig;
  std::shared_ptr<PenaltyContactForm> contact;  // obstacles as penalty contact (not energy-limited)
  Eigen::VectorXd lumped_masses;                // per vertex (dynamics)
  std::shared_ptr<MassMatrix> mass;             // the inertia's mass matrix (implicit dynamics)
  std::optional<EnergyLimit> energy_limit;
  std::unique_ptr<Integrator> integrator;
  State initial;  // rest positions and initial velocities

  // Boundary conditions, then bones (a bone wins on a shared vertex), at a frame number.
  void prescribe(double frame, Eigen::VectorXd& x, std::vector<char>& fixed) const;
};

Model build_model(const Scene& scene);

// The scene's constant external nodal forces (x[3 v + i] layout): gravity on the lumped masses,
// point loads (the force on each selected vertex), and tractions (force per rest area on the
// boundary faces whose vertices are all selected, distributed as t * integral of N_a over the
// face). Throws a sinew::Error naming the load's JSON path if a selection is empty or a
// traction selects no face.
Eigen::VectorXd external_forces(const Scene& scene, const Discretization& disc, const BoundarySurface& surface);

}  // namespace sinew
