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
#include "sinew/forms/inertia_form.hpp"
#include "sinew/forms/penalty_contact_form.hpp"
#include "sinew/integrator/integrator.hpp"
#include "sinew/mesh/surface.hpp"
#include "sinew/model/scene.hpp"
#include "sinew/model/scene_rig.hpp"

namespace sinew {

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
  Eigen::VectorXd external_forces;  // constant nodal forces: gravity, point loads, tractions
  std::vector<KinematicCondition> kinematics;  // the scene's boundary conditions, in order
  std::vector<int> boundary_owner;  // per vertex: the first boundary entry selecting it, or -1
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
