#include "sinew/scene/scene_constraints.hpp"

#include <fmt/format.h>

#include "sinew/scene/json_reader.hpp"

namespace sinew {

ConstraintsSpec parse_constraints(JsonObject o) {
  o.allow({"model", "time_step", "steps_per_frame", "initial_velocity", "energy_limit", "contact", "pgs", "sqp"});
  ConstraintsSpec spec;
  spec.model = o.choice("model", {"corotational", "material"}, "corotational");
  spec.step.time_step = o.positive("time_step", 0.01);
  spec.steps_per_frame = o.integer("steps_per_frame", 1, 1);
  spec.initial_velocity = o.vec3("initial_velocity", Eigen::Vector3d::Zero());
  if (o.has("energy_limit")) {
    JsonObject e = o.object("energy_limit");
    e.allow({"max_energy", "jacobian", "activation", "tolerance"});
    EnergyLimit limit;
    limit.max_energy = e.positive("max_energy");
    limit.jacobian = parse_jacobian_kind(e.choice("jacobian", {"exact", "warped"}, "exact"));
    if (limit.jacobian == JacobianKind::Warped && spec.model != "corotational")
      e.fail("jacobian", "the warped-force Jacobian exists only for the corotational model");
    spec.step.activation = e.number("activation", spec.step.activation);
    if (!(spec.step.activation >= 0.0 && spec.step.activation <= 1.0))
      e.fail("activation", fmt::format("must be in [0, 1], got {}", spec.step.activation));
    spec.step.energy_tolerance = e.positive("tolerance", spec.step.energy_tolerance);
    e.finish();
    spec.step.energy_limit = limit;
  }
  if (o.has("contact")) {
    JsonObject c = o.object("contact");
    c.allow({"ground", "friction", "tolerance"});
    JsonObject g = c.object("ground");
    g.allow({"normal", "offset", "margin"});
    GroundSpec ground;
    ground.normal = g.vec3("normal", ground.normal);
    if (!(ground.normal.norm() > 1e-12)) g.fail("normal", "must be a non-zero vector");
    ground.normal.normalize();
    ground.offset = g.number("offset", 0.0);
    ground.margin = g.number("margin", ground.margin);
    if (!(ground.margin >= 0.0)) g.fail("margin", fmt::format("must be non-negative, got {}", ground.margin));
    g.finish();
    spec.ground = ground;
    spec.friction = c.number("friction", 0.0);
    if (!(spec.friction >= 0.0)) c.fail("friction", fmt::format("must be non-negative, got {}", spec.friction));
    spec.step.contact_tolerance = c.positive("tolerance", spec.step.contact_tolerance);
    c.finish();
  }
  if (o.has("pgs")) {
    JsonObject p = o.object("pgs");
    p.allow({"iterations", "tolerance"});
    spec.step.pgs.max_iterations = p.integer("iterations", 1, spec.step.pgs.max_iterations);
    spec.step.pgs.tolerance = p.positive("tolerance", spec.step.pgs.tolerance);
    p.finish();
  }
  if (o.has("sqp")) {
    JsonObject s = o.object("sqp");
    s.allow({"iterations"});
    spec.step.sqp_max_iterations = s.integer("iterations", 1, spec.step.sqp_max_iterations);
    s.finish();
  }
  o.finish();
  return spec;
}

}  // namespace sinew
