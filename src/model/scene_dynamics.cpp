// The `dynamics` and `obstacles` sections of a scene (docs/dynamics.md).
#include <fmt/format.h>

#include "scene_sections.hpp"
#include "sinew/core/error.hpp"

namespace sinew {
namespace {

constexpr int kMaxSubsteps = 100000;

// `constrained`: the scene has a `constraints` section, whose stepper (paper 001 §5) is one
// linearised backward-Euler step with lumped mass, no damping and friction as constraints.
DynamicsSpec parse_dynamics(JsonObject o, bool constrained) {
  if (constrained) {
    if (o.has("integrator") && o.string("integrator", "") != "backward_euler")
      o.fail("integrator", "a scene with `constraints` is integrated by paper 001's linearised backward Euler; only \"backward_euler\" applies");
    if (o.has("mass") && o.string("mass", "") != "lumped")
      o.fail("mass", "the constrained stepper uses the lumped mass; only \"lumped\" applies with `constraints`");
    if (o.has("rayleigh")) o.fail("rayleigh", "Rayleigh damping is not available with `constraints`");
    if (o.has("friction_velocity"))
      o.fail("friction_velocity", "penalty-contact setting; constraint contact has exact Coulomb stick (no slip threshold)");
  }
  o.allow({"time_step", "substeps", "integrator", "mass", "rayleigh", "initial_velocity", "friction_velocity"});
  DynamicsSpec d;
  d.time_step = o.positive("time_step");
  d.substeps = o.integer("substeps", 1, 1);
  if (d.substeps > kMaxSubsteps) o.fail("substeps", fmt::format("must be at most {}, got {}", kMaxSubsteps, d.substeps));
  d.integrator = o.choice("integrator", {"backward_euler", "semi_implicit"}, "backward_euler") == "backward_euler"
                     ? DynamicsScheme::BackwardEuler
                     : DynamicsScheme::SemiImplicit;
  d.mass = o.choice("mass", {"lumped", "consistent"}, "lumped") == "lumped" ? MassKind::Lumped : MassKind::Consistent;
  if (o.has("rayleigh")) {
    JsonObject r = o.object("rayleigh");
    r.allow({"alpha", "beta"});
    d.rayleigh_alpha = r.number("alpha", 0.0);
    if (d.rayleigh_alpha < 0.0) r.fail("alpha", fmt::format("must be >= 0, got {}", d.rayleigh_alpha));
    d.rayleigh_beta = r.number("beta", 0.0);
    if (d.rayleigh_beta < 0.0) r.fail("beta", fmt::format("must be >= 0, got {}", d.rayleigh_beta));
    r.finish();
  }
  d.initial_velocity = o.vec3("initial_velocity", Eigen::Vector3d::Zero());
  d.friction_velocity = o.positive("friction_velocity", d.friction_velocity);
  o.finish();
  return d;
}

Eigen::Vector3d nonzero_vec3(JsonObject& o, const std::string& key) {
  const Eigen::Vector3d v = o.vec3(key);
  if (!(v.norm() > 0.0)) o.fail(key, "must be non-zero");
  return v;
}

std::shared_ptr<const ObstacleShape> parse_shape(JsonObject& o, const std::string& type) {
  const std::vector<std::string> common = {"name", "type", "stiffness", "friction", "motion"};
  auto allow = [&](std::vector<std::string> keys) {
    keys.insert(keys.end(), common.begin(), common.end());
    o.allow(keys);
  };
  if (type == "plane") {
    allow({"point", "normal"});
    return std::make_shared<PlaneObstacle>(o.vec3("point"), nonzero_vec3(o, "normal"));
  }
  if (type == "sphere") {
    allow({"center", "radius"});
    return std::make_shared<SphereObstacle>(o.vec3("center"), o.positive("radius"));
  }
  if (type == "capsule") {
    allow({"a", "b", "radius"});
    const Eigen::Vector3d a = o.vec3("a"), b = o.vec3("b");
    if (!((b - a).norm() > 0.0)) o.fail("b", "must differ from a");
    return std::make_shared<CapsuleObstacle>(a, b, o.positive("radius"));
  }
  if (type == "cylinder") {
    allow({"center", "axis", "radius", "length"});
    const Eigen::Vector3d center = o.vec3("center"), axis = nonzero_vec3(o, "axis");
    return std::make_shared<CylinderObstacle>(center, axis, o.positive("radius"), o.positive("length"));
  }
  allow({"min", "max"});
  const Eigen::Vector3d lo = o.vec3("min"), hi = o.vec3("max");
  if (!((hi - lo).array() > 0.0).all()) o.fail("max", "must exceed min in every coordinate");
  return std::make_shared<BoxObstacle>(lo, hi);
}

ObstacleSpec parse_obstacle(JsonObject o, bool dynamic, bool constrained) {
  if (!o.has("type")) o.fail("type", "missing (one of: plane, sphere, capsule, cylinder, box)");
  const std::string type = o.choice("type", {"plane", "sphere", "capsule", "cylinder", "box"}, "");
  ObstacleSpec s;
  s.shape = parse_shape(o, type);
  s.name = o.string("name", o.path());
  if (constrained) {
    // Constraint contact (paper 001 §5) has no penalty: the gap is held >= 0 within the tolerance.
    if (o.has("stiffness"))
      o.fail("stiffness", "penalty-contact setting; with `constraints` contact is a constraint (see constraints.contact)");
  } else {
    s.contact.stiffness = o.positive("stiffness");
  }
  s.contact.friction = o.number("friction", 0.0);
  if (s.contact.friction < 0.0) o.fail("friction", fmt::format("must be >= 0, got {}", s.contact.friction));
  if (s.contact.friction > 0.0 && !dynamic)
    o.fail("friction", "friction needs a `dynamics` section (slip is measured over a time step)");
  s.motion = o.has("motion") ? parse_motion(o.object("motion")) : RigidMotion{Pinned{}};
  o.finish();
  return s;
}

}  // namespace

void parse_dynamics_sections(JsonObject& root, Scene& scene) {
  const bool constrained = scene.constraints.has_value();
  if (root.has("dynamics")) scene.dynamics = parse_dynamics(root.object("dynamics"), constrained);
  if (constrained) {
    if (!scene.dynamics)
      root.fail("constraints", "needs a `dynamics` section (time_step, substeps, initial_velocity of the constrained steps)");
    scene.constraints->step.time_step = scene.dynamics->time_step / scene.dynamics->substeps;
  }
  if (root.has("obstacles"))
    for (JsonObject o : root.objects("obstacles"))
      scene.obstacles.push_back(parse_obstacle(o, scene.dynamics.has_value(), constrained));
}

}  // namespace sinew
